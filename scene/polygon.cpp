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
    const Vec2 e1 = outline[b] - outline[a], e2 = outline[c] - outline[a], d = at - outline[a];
    const double det = cross_2d(e1, e2);
    if (!(std::abs(det) > 0)) continue;
    const double v = cross_2d(d, e2) / det;
    const double w = cross_2d(e1, d) / det;
    const double u = 1 - v - w;
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
