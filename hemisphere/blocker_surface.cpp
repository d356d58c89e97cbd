#include "hemisphere/blocker_surface.h"

#include <cmath>

#include "geometry/clip.h"
#include "geometry/plane.h"

namespace rad {

std::optional<HemisphereProjection> project_onto_hemisphere(int id,
                                                            const std::vector<Vec3>& vertices,
                                                            const Vec3& normal, const Vec3& x,
                                                            const Vec3& n, double in_plane) {
  const double offset = plane_offset_from(x, vertices.front(), normal);
  if (std::abs(offset) <= in_plane) return std::nullopt;  // x in its plane: no solid angle
  std::vector<Vec3> relative;
  relative.reserve(vertices.size());
  for (const Vec3& v : vertices) relative.push_back(v - x);
  const std::vector<Vec3> clipped = clip_to_halfspace(relative, Vec3::Zero(), n);
  if (clipped.size() < 3) return std::nullopt;
  hemi::SphericalPolygon region(clipped);
  if (region.empty()) return std::nullopt;
  return HemisphereProjection{hemi::Occluder{id, normal, offset}, std::move(region)};
}

void BlockerSurface::add(int id, const std::vector<Vec3>& vertices, const Vec3& normal) {
  const auto p = project_onto_hemisphere(id, vertices, normal, x_, n_, in_plane_);
  if (!p) return;
  surface_.insert(p->occluder, p->region);
  ++inserted_;
}

double BlockerSurface::visible_form_factor(int id, const std::vector<Vec3>& vertices,
                                           const Vec3& normal) const {
  const auto p = project_onto_hemisphere(id, vertices, normal, x_, n_, in_plane_);
  if (!p) return 0;
  return surface_.visible_form_factor(p->occluder, p->region, n_);
}

}  // namespace rad
