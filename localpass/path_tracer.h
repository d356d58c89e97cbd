#pragma once
/// An unbiased path tracer of the scene itself (no solution): the independent reference the
/// whole pipeline is measured against, as Radiance was for the opaque Cornell box. Every bounce
/// is sampled. From x, a cosine-weighted direction is followed through filters and off mirrors
/// (RayCaster::follow: both are deterministic splits, weighted by transmittance and specular
/// reflectance); at each front-facing surface y met, the estimate gains E(y) + rho(y) H(y), and
/// H(y) is estimated the same way from one new cosine-weighted direction at y. Since
/// H = integral of (B / pi) cos theta dw, one cosine-weighted sample of B estimates H without a
/// weight. Russian roulette after the second bounce keeps a path with probability
/// q = min(0.95, max_c rho) and divides by q, so the estimate stays unbiased.
#include <cstdint>

#include "scene/ray_caster.h"
#include "scene/scene.h"

namespace rad {

struct PathTraceEstimate {
  Rgb mean = Rgb::Zero();            ///< H(x) [W/m^2]
  Rgb standard_error = Rgb::Zero();  ///< Of the mean, from the spread of the paths
};

class PathTracer {
 public:
  /// The scene must outlive the tracer.
  explicit PathTracer(const Scene& scene);

  /// H(x) at unit normal n from `paths` paths, seeded by `seed` (e.g. the point's index): the
  /// same seed gives the same estimate on any thread. Thread-safe.
  PathTraceEstimate irradiance(const Vec3& x, const Vec3& n, int paths, uint64_t seed) const;

 private:
  const Scene& scene_;
  RayCaster caster_;
  double offset_ = 0;  ///< Rays start this far along the normal, off the surface
};

}  // namespace rad
