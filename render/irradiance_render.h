#pragma once
/// Images of B(x) = E(x) + rho(x) H(x) at the primary hit of every pixel (and, through filters,
/// at the surfaces behind, weighted by what the filters pass: 000 §2.2), with H from the
/// error-bounded local pass (exact, with a certified bound) or from the Monte Carlo baseline,
/// and what each pixel cost.
#include <functional>
#include <utility>
#include <vector>

#include "distributed/job.h"
#include "formats/image.h"
#include "localpass/local_pass.h"
#include "reference/monte_carlo.h"
#include "reference/path_tracer.h"
#include "scene/camera.h"
#include "scene/ray_caster.h"

namespace rad {

struct IrradianceImage {
  /// B = E + rho H [W/m^2] at front-facing primary hits, 0 elsewhere; through filters, the
  /// sum of the B of the surfaces along the eye ray, each times the transmittances in front.
  Image radiosity;
  /// Of `radiosity`, the part refracted through transparent polyhedra by the heuristic of 000 §4
  /// (w rho H_refracted): not covered by `bound`, which bounds radiosity - refracted.
  Image refracted;
  /// Of `radiosity`, the part from point sources by way of glossy surfaces (003's beams, w rho
  /// H_glossy) and the point lights' highlights on glossy surfaces the eye sees: not covered by
  /// `bound` either.
  Image glossy;
  Image bound;  ///< Sum of w rho * H's certified bound: |B - B_exact| <= bound (0 for Monte Carlo)
  /// Per pixel: faces gathered exactly (0 at misses, back sides, Monte Carlo; summed over the
  /// surfaces seen through filters, as the next two)
  std::vector<int> gathered_exactly;
  std::vector<int> projected;  ///< Per pixel: faces projected (hemisphere: with possible occluders)
  std::vector<int> clusters;   ///< Per pixel: cluster intervals computed (localpass/cluster_tree.h)
  std::vector<char> surface;   ///< Per pixel: 1 where a front-facing surface was gathered
  /// Per pixel: 1 where an interpolation cell's certified interpolation gave its smooth part
  /// (localpass/tile_gather.h; LocalPass::tile() sets the cells' side)
  std::vector<char> interpolated;
  int samples_per_pixel = 0;  ///< Monte Carlo: rays per pixel; 0 for the exact local pass

  /// The heuristic parts by name ("refracted", "glossy"), each apart from the bound.
  std::vector<std::pair<const char*, const Image*>> heuristic_parts() const {
    return {{"refracted", &refracted}, {"glossy", &glossy}};
  }
  /// The part of pixel i's B that `bound` covers: B less the heuristic parts.
  Rgb certified_part(size_t i) const {
    return radiosity.pixels[i] - refracted.pixels[i] - glossy.pixels[i];
  }
};

/// Per-pixel counts and bounds summed up over the pixels where a surface was gathered (the
/// render's stats JSON, the sweep's table).
struct IrradianceSummary {
  size_t pixels = 0;  ///< pixels gathered
  double gathered_exactly_mean = 0, projected_mean = 0, clusters_mean = 0;
  size_t interpolated = 0;  ///< pixels whose smooth part an interpolation cell gave
  int gathered_exactly_max = 0, projected_max = 0;
  double bound_max = 0;  ///< largest bound, largest channel
  /// bound / B per pixel (largest channels; 0 where B = 0): mean and max.
  double relative_bound_mean = 0, relative_bound_max = 0;
};
IrradianceSummary summarize(const IrradianceImage& image);

/// The side of the square tiles an MPI job's render hands out (the last row and column may be
/// smaller): 64 pixels, halved down to 16 until there are 8 tiles a process, so that the dynamic
/// schedule has slack to even out uneven tiles.
int tile_side(int width, int height, int processes);

/// The reference: B = E + rho H at the visible points with H from `paths` paths of the path
/// tracer of the scene itself (reference/path_tracer.h; no solution), seeded by the pixel
/// index (bitwise the same for any thread count).
IrradianceImage render_path_traced(const Scene& scene, const RayCaster& caster,
                                   const Camera& camera, const PathTracer& tracer, int paths,
                                   const std::function<void(size_t)>& progress = {},
                                   const Job& job = Job::world());

/// Renders through `camera` with the local pass at `tolerance`; parallel over 16x16 pixel tiles
/// (TBB). With the pass's interpolation cells (LocalPass::tile() > 1, tolerance > 0, one
/// process), the pixels on every tile-th row and column are gathered first; a cell between
/// them whose pixels all see one polygon directly (no filter or mirror on the way) is gathered
/// by LocalPass::gather_tile, every other pixel on its own; every pixel keeps its certified
/// bound. The image is bitwise the same for any thread count. `progress` (may be empty) is called
/// with the number of pixels done, from worker threads, now and then. Over an MPI job (`job` of
/// more than one process) the tiles are spread over its processes and the whole image is on the
/// root alone; it is bitwise the same image (and on the other processes these functions return
/// partial images).
IrradianceImage render_local_pass(const Scene& scene, const RayCaster& caster, const Camera& camera,
                                  const LocalPass& pass, double tolerance,
                                  const std::function<void(size_t)>& progress = {},
                                  const Job& job = Job::world());

/// The Monte Carlo baseline: H from `samples` cosine-weighted rays per pixel, seeded by the
/// pixel index (bitwise the same for any thread count).
IrradianceImage render_monte_carlo(const Scene& scene, const RayCaster& caster,
                                   const Camera& camera, const MonteCarloGatherer& gatherer,
                                   int samples, const std::function<void(size_t)>& progress = {},
                                   const Job& job = Job::world());

}  // namespace rad
