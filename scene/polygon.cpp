#include "scene/polygon.h"

#include <algorithm>
#include <cmath>

namespace rad {

Vec3 shading_normal(const Polygon& p, const Vec3& x) {
  if (p.vertex_normals.size() != p.vertices.size()) return p.normal;
  const std::vector<Vec2> outline = project_to_plane(p.vertices, p.normal);
  const PlaneFrame frame(p.vertices.front(), p.normal);  // as project_to_plane
  const Vec2 at = frame.to_2d(x);
  // The triangle that holds x best (largest smallest barycentric weight), weights clamped.
  double best = -INFINITY;
  Vec3 normal = p.normal;
  for (const auto& [a, b, c] : triangulate(outline)) {
    const auto weights = barycentric_2d(outline[a], outline[b], outline[c], at);
    if (!weights) continue;
    const auto [u, v, w] = *weights;
    const double least = std::min({u, v, w});
    if (least <= best) continue;
    best = least;
    const Vec3 sum = std::max(u, 0.0) * p.vertex_normals[a] +
                     std::max(v, 0.0) * p.vertex_normals[b] +
                     std::max(w, 0.0) * p.vertex_normals[c];
    if (sum.norm() > 0) normal = sum.normalized();
  }
  return normal;
}

}  // namespace rad
