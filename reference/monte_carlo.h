#pragma once
/// The Monte Carlo final gather: the baseline users would otherwise pick. Cosine-weighted rays
/// from x into the solution; each ray returns the radiosity of the element it hits first (its
/// front side; a back side or a miss returns 0), and H = the mean of those radiosities (the
/// cosine-weighted estimator of H = integral of (B / pi) cos theta dw). A ray passes on through
/// filters (000 §2.2) and reflects off mirrors (000 §3, to the scene's mirror depth), collecting
/// each surface's front radiosity weighted by what the filters and mirrors before it passed
/// on, and ends at the first opaque polygon. Point lights, which no ray can hit, add their
/// direct light as it is, straight and by the mirrors' images (scene/point_lights.h). Seeded per
/// point, so a result does not depend on the order or the thread it is computed in.
#include <cstdint>
#include <memory>
#include <vector>

#include "scene/point_lights.h"
#include "scene/polygon_faces.h"
#include "scene/ray_caster.h"
#include "scene/scene.h"

namespace rad {

class MonteCarloGatherer {
 public:
  /// The faces become the polygons of a scene of their own, so that a hit names its face.
  MonteCarloGatherer(const Scene& scene, const std::vector<EmittingFace>& faces);
  ~MonteCarloGatherer();

  /// Estimate of H(x) from `samples` stratified (sqrt(samples)^2 strata, rounded up) jittered
  /// cosine-weighted directions; `seed` picks the jitter (e.g. the pixel index). Thread-safe.
  Rgb gather(const Vec3& x, const Vec3& n, int samples, uint64_t seed) const;

 private:
  Scene faces_scene_;
  std::vector<Rgb> exitance_;
  std::unique_ptr<RayCaster> caster_;
  std::unique_ptr<PointLightIrradiance> lights_;
  double offset_ = 0;  ///< Rays start this far along the normal, off the receiver's own face
};

}  // namespace rad
