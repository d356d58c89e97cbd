#pragma once
/// The accuracy-versus-tolerance experiment (paper 004 §5, Fig. 7): render the exact reference
/// once, then every method at every setting; compare each image with the reference; write the
/// table (results.csv), the images, their error maps and the charts.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "distributed/job.h"
#include "experiments/error_map.h"
#include "geometry/emitting_face.h"
#include "localpass/method.h"
#include "render/irradiance_render.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace rad {

struct SweepSettings {
  std::vector<Method> methods{Method::hemisphere, Method::montecarlo};
  std::vector<double> tolerances{0, 0.05, 0.2};  ///< for hemisphere and vertex
  std::vector<int> samples{16, 64, 256, 1024};   ///< for montecarlo
  /// The reference is the tolerance-0 image of this exact method. A tolerance-0 row of the same
  /// method is the reference render itself (timed once, error 0 by construction).
  Method reference_method = Method::hemisphere;
  /// When set: an exact image from an earlier run (a sweep's reference.exr, or a tolerance-0
  /// render) used as the reference instead of rendering one; it must have the camera's size.
  /// Its float precision limits agreement to ~1e-7, so the bound check allows 2^-23 of the
  /// reference instead of 1e-8, and a tolerance-0 row is rendered like any other.
  std::filesystem::path reference_file;
};

/// One row of results.csv.
struct SweepRow {
  Method method = Method::hemisphere;
  double tolerance = 0;  ///< exact methods
  int samples = 0;       ///< montecarlo
  double seconds = 0;    ///< the render alone (faces and octree set up before the clock)
  double projected_mean = 0, projected_max = 0;  ///< faces projected per pixel; 0 for montecarlo
  ErrorStats error;                              ///< relative to the reference (error_map.h)
  /// Pixels where |B - B_ref| > bound on some channel (beyond 1e-12 relative rounding slack);
  /// -1 for montecarlo, which has no bound.
  long violations = -1;
  double error_over_bound_max = 0;  ///< max over pixels of |B - B_ref| / bound, where bound > 0
  std::string image;                ///< file name of its image, relative to the output folder

  bool exact() const { return is_exact(method); }
  std::string label() const;  ///< "hemisphere T=0.05", "montecarlo N=64"
  std::string slug() const;   ///< "hemisphere_T0.05", "montecarlo_N64"
};

/// Per-pixel comparison of a local-pass image with the reference: the relative error map and
/// the bound check (SweepRow's error, violations, error_over_bound_max).
/// `slack` is the fraction of the reference's value an excess over the bound may have and
/// still count as rounding.
void compare_to_reference(const IrradianceImage& image, const IrradianceImage& reference,
                          SweepRow& row, ErrorMap* map = nullptr, double slack = 1e-8);

/// Reports progress: `what` is being rendered, `done` of it in [0, 1].
using SweepProgress = std::function<void(const std::string& what, double done)>;

/// Called after each row is measured and its image written.
using SweepRowDone = std::function<void(const SweepRow& row)>;

/// What a sweep measured: the rows in the order of results.csv, their error maps, and the one
/// colour scale for the heat maps (the largest error of the exact rows, where Monte Carlo's
/// maps clamp; with no exact row, the largest of all).
struct SweepResult {
  std::vector<SweepRow> rows;
  std::vector<ErrorMap> maps;
  double error_scale = 0;
};

/// Runs the sweep and writes into `folder`: results.csv; reference.exr/.png; images/<slug>.exr
/// and .png; error_maps/<slug>.exr. The pictures (heat maps and charts) are viz's
/// (viz/sweep_figures.h). Throws Error. Over an MPI job (`job`, distributed/job.h) every process
/// calls it: each render's tiles are spread over them, and the root alone compares, writes and
/// returns the rows (the others return none).
SweepResult run_sweep(const Scene& scene, const std::vector<EmittingFace>& faces,
                      const Camera& camera, const SweepSettings& settings,
                      const std::filesystem::path& folder, const SweepProgress& progress = {},
                      const SweepRowDone& row_done = {}, const Job& job = Job::world());

/// results.csv: a header and one line per row (columns documented in docs/formats.md).
void write_sweep_csv(const std::filesystem::path& file, const std::vector<SweepRow>& rows);

/// A number as results.csv writes it (10 significant digits).
std::string csv_number(double v);

}  // namespace rad
