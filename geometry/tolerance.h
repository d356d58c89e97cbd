#pragma once
/// The scene's tolerance policy, one value for everyone. The culling of the local pass is exact
/// only if it decides "x lies in this polygon's plane" exactly as the gatherers do, so the
/// gatherers and the culling receive their tolerances from this one place (Scene::tolerance()).
namespace rad {

struct Tolerance {
  /// |plane offset| at or below this: x lies in the polygon's plane, which then subtends no
  /// solid angle (both gatherers skip the polygon; the culling skips it as a blocker). Also the
  /// shortest interpenetration segment vertex tracing keeps.
  double in_plane = 0;
  /// Conservative padding and matching: the culling's shafts and box sweeps are grown by it (so
  /// rounding errors stay on the safe side); points this close are one vertex when element
  /// meshes are welded, and an element edge this close to its polygon's edge lies on it.
  double pad = 0;
  /// Monte Carlo rays start this far along the normal, off the receiver's own face (Embree
  /// intersects in float).
  double ray_offset = 0;

  /// The policy for a scene whose bounding box has this diagonal: 1e-12 of it in the plane
  /// (far above the rounding of coordinates, far below any feature a scene models), 1e-9 as
  /// padding, 1e-6 as the ray offset.
  static Tolerance for_scene_size(double diagonal) {
    return {1e-12 * diagonal, 1e-9 * diagonal, 1e-6 * diagonal};
  }
};

}  // namespace rad
