#pragma once
/// Exact visibility of point lights for the local pass (issue 20): what passes along the
/// segment from x to a light, decided in double precision against the polygons themselves
/// (not Embree's single-precision traversal with a ray offset, as scene/point_lights.h does for
/// the solver and the path tracer, which places a shadow's edge only to within the offset,
/// 1e-6 of the scene's diagonal).
///
/// Why it is exact: a polygon P hides part of the segment [x, L] only if x and L lie strictly on
/// opposite sides of P's plane (x in P's plane: P is edge-on to x and hides nothing, as for the
/// exact gatherers; L in it: a light on a wall is not hidden by the wall), and then only at the
/// one point where the segment meets the plane, which is hidden exactly when it lies in P's
/// outline (boundary included). Only polygons that may hide anything from x (the culling's
/// candidates: off x's plane, partly above its horizon) are asked, and a light below the
/// horizon gives nothing anyway. The product of the transmittances of the polygons met (0 for
/// an opaque one) is what passes (000 §2.2). Rounding (~1e-16 relative) is the only error.
#include <span>
#include <vector>

#include "geometry/vec.h"
#include "scene/polygon.h"
#include "scene/scene.h"

namespace rad {

class PointLightVisibility {
 public:
  explicit PointLightVisibility(const Scene& scene);

  /// Sum over the scene's lights of I max(0, n . w) / r^2 times what the polygons among
  /// `candidates` pass along the segment from x to the light.
  Rgb irradiance(const Vec3& x, const Vec3& n, std::span<const int> candidates) const;

 private:
  struct Plane {
    PlaneFrame frame;           ///< Origin at the polygon's first vertex, n its normal
    double offset;              ///< n . (a point of the plane)
    std::vector<Vec2> outline;  ///< The polygon in the frame
    Rgb transmittance;          ///< 0 for an opaque polygon
  };
  const Scene& scene_;
  std::vector<Plane> planes_;
  double in_plane_;
};

}  // namespace rad
