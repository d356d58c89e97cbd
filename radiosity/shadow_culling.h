#pragma once
/// Which (receiver point, shooter) pairs of the solve need shadow rays at all: shaft culling
/// (Haines and Wallace 1994) against the scene's polygons. Most pairs in a room have nothing
/// between them; their visible fraction is 1 and the solver casts no rays for them.
#include <Eigen/Geometry>
#include <vector>

#include "geometry/vec.h"
#include "scene/scene.h"

namespace rad {

class ShadowCulling {
 public:
  /// `pad`: how far on the safe side the tests err, in scene units (the solver passes its ray
  /// offset, far above the ray caster's float rounding).
  ShadowCulling(const Scene& scene, double pad);

  /// False only when no polygon other than the receiver's and the shooter's can meet a segment
  /// from x to the convex shooter outline `corners`: every polygon either has x and all the
  /// corners strictly on one side of its plane (by more than pad), or misses the shaft from x
  /// to the corners' box (geometry/shaft.h, padded). Then no segment is blocked: each lies in
  /// the shaft, and a segment meets a plane that does not separate its ends only where it
  /// lies in it. The receiver's own plane holds x (a segment leaves it there), the shooter's
  /// holds the far end. Cost: a box test per polygon (against the shaft's box), a plane test
  /// for those inside it, the shaft (built once) for the rest.
  bool may_be_hidden(const Vec3& x, int receiver, const std::vector<Vec3>& corners,
                     int shooter) const;

 private:
  const Scene& scene_;
  std::vector<Eigen::AlignedBox3d> boxes_;  ///< Per scene polygon
  double pad_;
};

}  // namespace rad
