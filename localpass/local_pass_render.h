#pragma once
/// The local pass as an image: per pixel, the primary hit x and B(x) = E(x) + rho(x) H(x) with
/// H from LocalPass at a tolerance, and what each pixel cost.
#include <functional>
#include <vector>

#include "localpass/image.h"
#include "localpass/local_pass.h"
#include "localpass/monte_carlo.h"
#include "scene/camera.h"
#include "scene/ray_caster.h"

namespace rad {

struct LocalPassImage {
  Image radiosity;              ///< B = E + rho H [W/m^2] at front-facing primary hits; 0 elsewhere
  Image bound;                  ///< rho * H's certified bound: |B - B_exact| <= bound, per channel
  std::vector<int> emitting;    ///< Per pixel: faces gathered exactly (0 at misses and back sides)
  std::vector<int> projected;   ///< Per pixel: faces projected (hemisphere: with possible occluders)
  std::vector<char> surface;    ///< Per pixel: 1 where a front-facing surface was gathered
};

/// Per-pixel counts and bounds summed up over the pixels where a surface was gathered (the
/// render's stats JSON, the sweep's table).
struct LocalPassSummary {
  size_t pixels = 0;  ///< pixels gathered
  double emitting_mean = 0, projected_mean = 0;
  int emitting_max = 0, projected_max = 0;
  double bound_max = 0;  ///< largest bound, largest channel
  /// bound / B per pixel (largest channels; 0 where B = 0): mean and max.
  double relative_bound_mean = 0, relative_bound_max = 0;
};
LocalPassSummary summarize(const LocalPassImage& image);

/// Renders through `camera`; parallel over 16x16 pixel tiles (TBB). Every pixel is computed on
/// its own, so the image is bitwise the same for any thread count. `progress` (may be empty) is
/// called with the number of pixels done, from worker threads, now and then.
LocalPassImage render_local_pass(const Scene& scene, const RayCaster& caster, const Camera& camera,
                                 const LocalPass& pass, double tolerance,
                                 const std::function<void(size_t)>& progress = {});

/// The Monte Carlo baseline as an image: B = E + rho H with H from `samples` cosine-weighted
/// rays per pixel, seeded by the pixel index (bitwise the same for any thread count). `surface`
/// as above; emitting/projected hold the samples.
LocalPassImage render_monte_carlo(const Scene& scene, const RayCaster& caster, const Camera& camera,
                                  const MonteCarloGatherer& gatherer, int samples,
                                  const std::function<void(size_t)>& progress = {});

}  // namespace rad
