// `radiosity sweep SCENE --solution S.vtp -o DIR [--tolerances ...] [--methods ...] [--samples
// ...]`: the accuracy-versus-tolerance experiment (experiments/sweep.h): results.csv, images, error
// maps, charts.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/common.h"
#include "cli/inputs.h"
#include "cli/methods.h"
#include "distributed/job.h"
#include "experiments/sweep.h"
#include "radiosity/solution_faces.h"
#include "viz/offscreen_display.h"
#include "viz/sweep_figures.h"

namespace rad::cli {
namespace {

struct SweepOptions {
  std::string scene, solution, output;
  std::vector<std::string> methods{"hemisphere", "montecarlo"};
  std::string reference_method = "hemisphere";
  SweepSettings settings;
  int width = 0, height = 0;
  int threads = 0;
};

void run_sweep_command(SweepOptions o) {
  const auto start = std::chrono::steady_clock::now();
  o.settings.methods.clear();
  for (const std::string& name : o.methods)
    o.settings.methods.push_back(*method_traits(name).local);  // CLI11 checked
  o.settings.reference_method = *method_traits(o.reference_method).local;
  // Over an MPI job every process renders tiles; the root alone draws and writes.
  const Job& job = Job::world();
  // The charts and heat maps need a display: fail now, not after the renders.
  job.step([&] {
    if (job.is_root()) ensure_display();
  });
  const ThreadLimit limit(o.threads);
  const Inputs inputs = load_inputs(job, o.scene, o.solution);
  const Scene& scene = inputs.scene;
  CameraSpec spec;
  std::vector<EmittingFace> faces;
  job.step([&] {
    spec = camera_for(scene, o.scene, "sweep", o.width, o.height);
    faces = faces_from_solution(scene, *inputs.solution);
  });
  const Camera camera(spec);
  std::cerr << "sweep: " << camera.width() << "x" << camera.height() << ", " << faces.size()
            << " elements; the reference is "
            << (o.settings.reference_file.empty() ? o.reference_method + " at tolerance 0"
                                                  : o.settings.reference_file.string())
            << "\n";

  ProgressBar bar("sweep");
  const auto progress = [&](const std::string& what, double done) {
    bar.update(done, what + " " + std::to_string(static_cast<int>(100 * done)) + "%");
  };
  const auto on_row = [&](const SweepRow& row) {
    bar.finish();
    std::cerr << "sweep: " << row.label() << ": " << row.seconds << " s, max error "
              << row.error.max << ", RMS " << row.error.rms;
    if (row.exact()) std::cerr << ", bound violations " << row.violations;
    std::cerr << "\n";
  };
  const SweepResult sweep =
      run_sweep(scene, faces, camera, o.settings, o.output, progress, on_row, job);
  bar.finish();
  if (!job.is_root()) return;
  write_sweep_figures(o.output, sweep);
  const std::vector<SweepRow>& rows = sweep.rows;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cerr << "sweep: " << rows.size() << " settings in " << seconds << " s; wrote " << o.output
            << "/results.csv, error_vs_tolerance.png, time_vs_tolerance.png, error_vs_time.png, "
               "reference.exr, "
               "images/, error_maps/\n";
}

}  // namespace

void add_sweep_command(CLI::App& app, Run& run) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* sub =
      app.add_subcommand("sweep",
                         "Accuracy against tolerance: render the exact reference once, then each "
                         "method at each setting; write "
                         "results.csv, the images, error maps and charts (PNG) to a folder.");
  sub->footer(
      "Writes to the folder: results.csv (one row per method and setting: seconds, faces "
      "projected,\n"
      "max/mean/RMS relative error against the reference, bound violations, largest error over "
      "bound;\n"
      "docs/formats.md), reference.exr/.png, images/<method>_T<t>.exr/.png and\n"
      "images/montecarlo_N<n>.exr/.png, error_maps/<same>.exr/.png (heat maps on one colour scale: "
      "the\n"
      "largest error of the exact rows; Monte Carlo's maps clamp there), and three charts with "
      "log\n"
      "axes: error_vs_tolerance.png (with T / (1 - T), what the bound promises against the exact\n"
      "value), time_vs_tolerance.png, error_vs_time.png. A tolerance-0 row of the reference method "
      "is\n"
      "the reference render itself. With --reference the reference holds floats, so the bound "
      "check\n"
      "allows 2^-23 of the value instead of 1e-8. Prints a line per setting; timings are of the\n"
      "renders alone. Pictures need an X display: without $DISPLAY a private Xvfb is started.\n"
      "Under mpirun each render's tiles are spread over the processes (docs/cluster.md).");
  sub->add_option("scene", o->scene, kSceneHelp)->required();
  add_solution_option(sub, &o->solution)->required();
  sub->add_option("-o,--output", o->output, "Output folder (created if missing)")->required();
  sub->add_option("--methods", o->methods, "Methods to run: hemisphere, vertex, montecarlo")
      ->delimiter(',')
      ->check(CLI::IsMember(method_names_for(MethodCommand::sweep)))
      ->capture_default_str();
  sub->add_option("--tolerances", o->settings.tolerances,
                  "hemisphere/vertex: tolerances to run, each in [0, 0.99] (0: exact)")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 0.99))
      ->check(kFinite)
      ->capture_default_str();
  sub->add_option("--samples", o->settings.samples, "montecarlo: rays per pixel to run, each >= 1")
      ->delimiter(',')
      ->check(CLI::Range(1, 1 << 24))
      ->capture_default_str();
  sub->add_option("--reference-method", o->reference_method,
                  "Exact method whose tolerance-0 image is the reference")
      ->check(CLI::IsMember(exact_method_names_for(MethodCommand::sweep)))
      ->capture_default_str();
  sub->add_option("--reference", o->settings.reference_file,
                  "An exact image of the same size from an earlier run (e.g. a sweep's "
                  "reference.exr) to use as "
                  "the reference instead of rendering one");
  add_image_size_options(sub, &o->width, &o->height);
  add_threads_option(sub, &o->threads);
  sub->callback([o, &run] { run = [o] { run_sweep_command(*o); }; });
}

}  // namespace rad::cli
