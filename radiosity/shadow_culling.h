#pragma once
/// Which (receiver point, shooter) pairs of the solve need shadow rays at all: shaft culling
/// (Haines and Wallace 1994) against the scene's polygons. Most pairs in a room have nothing
/// between them; their visible fraction is 1 and the solver casts no rays for them.
#include <Eigen/Geometry>
#include <functional>
#include <vector>

#include "geometry/box_tree.h"
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
  /// holds the far end. Cost: a descent of the polygons' box tree to those whose boxes meet
  /// the shaft's box (the rest miss the shaft), a plane test for each, the shaft (built once)
  /// for those no plane separates. (A pass over every polygon was half the solve's time on a
  /// building of 46,000 polygons.) It gives up, true, past a few hundred polygons in the
  /// shaft's box: true is always safe, the rays then decide.
  ///
  /// `on_the_way`, when given, is asked once, before the shaft is built (the scan's dear step,
  /// at the first polygon no plane separates); its true ends the scan with true. It must be
  /// true only when some polygon other than the receiver's and the shooter's meets a segment
  /// from x to the outline (the solver's: Shooter::something_on_the_way, one ray), so the
  /// answer is the same: that polygon's box meets the shaft's box, no plane separates the
  /// segment's ends, the shaft holds the segment, and the scan would have said true on
  /// reaching it. In a furnished room nearly every pair has something between and the shaft's
  /// box holds hundreds of polygons (books): the scans were 60% of a solve of data/building.
  bool may_be_hidden(const Vec3& x, int receiver, const std::vector<Vec3>& corners, int shooter,
                     const std::function<bool()>& on_the_way = {}) const;

 private:
  const Scene& scene_;
  BoxTree<3> boxes_;  ///< Of the scene's polygons
  double pad_;
};

}  // namespace rad
