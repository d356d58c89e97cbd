#pragma once
/// The visible surface of a few occluding polygons at one point, queried for the exact visible
/// form factor of other polygons among them without inserting those (hemisphere/visible_surface.h).
/// The local pass uses it for whatever its culling says may be hidden (localpass/local_pass.h):
/// the blockers are whole scene polygons (a block face is one insertion, not 36-60 elements),
/// and each partly hidden cluster or face costs one walk down the tree.
#include <optional>
#include <vector>

#include "geometry/tolerance.h"
#include "hemisphere/visible_surface.h"

namespace rad {

/// A planar convex polygon (absolute coordinates, plane normal `normal`) as seen from x: its
/// part above x's horizon (normal n) on the unit sphere, with its plane relative to x. Nothing
/// when x is in its plane (|offset| <= in_plane) or nothing of it is above the horizon.
struct HemisphereProjection {
  hemi::Occluder occluder;
  hemi::SphericalPolygon region;
};
std::optional<HemisphereProjection> project_onto_hemisphere(int id,
                                                            const std::vector<Vec3>& vertices,
                                                            const Vec3& normal, const Vec3& x,
                                                            const Vec3& n, double in_plane);

class BlockerSurface {
 public:
  BlockerSurface(const Vec3& x, const Vec3& n, const Tolerance& tolerance)
      : x_(x), n_(n), in_plane_(tolerance.in_plane) {}

  /// Inserts a convex polygon that hides from both sides. `id` settles coplanar overlaps: the
  /// lower id shows (as in both gatherers, where faces are ordered by polygon).
  void add(int id, const std::vector<Vec3>& vertices, const Vec3& normal);
  /// Exact form factor of the part of this convex polygon that no inserted polygon hides.
  double visible_form_factor(int id, const std::vector<Vec3>& vertices, const Vec3& normal) const;
  bool empty() const { return inserted_ == 0; }

 private:
  Vec3 x_, n_;
  double in_plane_;
  int inserted_ = 0;
  hemi::VisibleSurface surface_;
};

}  // namespace rad
