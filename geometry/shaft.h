#pragma once
/// The shaft from a point to a box: their convex hull (Haines and Wallace's shaft culling, with
/// one end shrunk to the point). Whatever hides any part of the box from x meets it, so a
/// polygon certainly outside it can be left out of the visibility work for that box.
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "geometry/vec.h"

namespace rad {

class Shaft {
 public:
  /// The hull of x and `box` grown by `pad` on every side (so flat boxes have volume, and
  /// rounding errors of size pad are on the safe side).
  Shaft(const Vec3& x, Eigen::AlignedBox3d box, double pad);
  /// A shaft that holds the hull of two boxes (every segment from a point of `from` to a point
  /// of `box`, grown by `pad`): the shaft from `from`'s centre c, with its planes moved out by
  /// `from`'s half diagonal rho too. Why it holds them: a point of the hull is
  /// t (c + e) + (1 - t) y with |e| <= rho, within rho of t c + (1 - t) y, which lies in the
  /// shaft from c; moving every plane of a convex polyhedron out by rho takes in everything
  /// within rho of it, and the bounding box is grown to hold `from` as well.
  Shaft(const Eigen::AlignedBox3d& from, const Eigen::AlignedBox3d& box, double pad);

  /// False only when the polygon with these vertices certainly misses the shaft: its box misses
  /// the shaft's box, or clipping it by the shaft's planes (moved out by pad) leaves nothing.
  /// Exact for a convex polygon; conservative for a concave one (it may still miss).
  bool may_meet(const std::vector<Vec3>& vertices) const;
  bool may_meet(const std::vector<Vec3>& vertices, const Eigen::AlignedBox3d& vertex_box) const;
  /// The same for a whole box (its corners).
  bool may_meet(const Eigen::AlignedBox3d& box) const;

 private:
  struct Plane {
    Vec3 normal;    ///< Unit, pointing out of the shaft.
    double offset;  ///< The shaft lies where normal . p <= offset.
  };
  Eigen::AlignedBox3d hull_box_;
  std::array<Plane, 12> planes_;  ///< At most 6 box faces plus 6 silhouette planes
  int plane_count_ = 0;
  double pad_ = 0;
};

}  // namespace rad
