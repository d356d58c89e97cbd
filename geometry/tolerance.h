#pragma once
/// The scene's tolerance policy, one value for everyone. The culling of the local pass is exact
/// only if it decides "x lies in this polygon's plane" exactly as the gatherers do, so the
/// gatherers and the culling receive their tolerances from this one place (Scene::tolerance()).
namespace rad {

/// The relative epsilons, each a fraction of a scale named where it is used (a length, an area,
/// a cosine, a parameter): one place, so that the code that must agree on a decision takes the
/// same fraction.
namespace relative {
/// Equal up to the rounding of a few double operations: 1e-12.
inline constexpr double kRounding = 1e-12;
/// Matching and padding, far above rounding and far below any feature a scene models: 1e-9.
inline constexpr double kMatch = 1e-9;
/// Float precision (Embree intersects in float; authored coordinates are often floats): 1e-6.
inline constexpr double kFloat = 1e-6;
}  // namespace relative

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
    return {relative::kRounding * diagonal, relative::kMatch * diagonal,
            relative::kFloat * diagonal};
  }
};

}  // namespace rad
