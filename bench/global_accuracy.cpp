// The global solution against the converged path-traced reference (issue 18): for each bundled
// scene with accuracy points (data/<scene>/accuracy-points.csv, accuracy-reference.csv), the
// solve at several patch sizes (default settings otherwise) and the exact local pass at the
// points: errors against the reference, solve seconds, patches, elements, shots. Prints
// Markdown tables (bench/global_accuracy.sh writes them to bench/results/global_accuracy.md) and
// draws the error against solve time as a PNG.
// Usage: global_accuracy [CHART.png]
#include "experiments/global_accuracy.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "localpass/local_pass.h"
#include "radiosity/solution_faces.h"
#include "radiosity/solver.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "viz/charts.h"

namespace {

struct Run {
  double patch_size = 0;
  rad::SolveStats stats;
  double seconds = 0;  ///< median over the runs made
  rad::AccuracyReport report;
};

Run measure(const rad::Scene& scene, const std::vector<rad::ReferencePoint>& reference,
            double patch_size, int repeats) {
  const rad::RayCaster caster(scene);
  rad::SolverSettings settings;
  settings.patch_size = patch_size;
  Run run;
  run.patch_size = patch_size;
  std::vector<double> seconds;
  rad::Solution solution;
  for (int i = 0; i < repeats; ++i) {
    solution = rad::solve(caster, settings);
    seconds.push_back(solution.stats.seconds);
  }
  std::sort(seconds.begin(), seconds.end());
  run.seconds = seconds[seconds.size() / 2];
  run.stats = solution.stats;
  const rad::LocalPass pass(scene, rad::faces_from_solution(scene, solution),
                            rad::Method::hemisphere);
  std::vector<rad::Rgb> values;
  for (const rad::ReferencePoint& r : reference)
    values.push_back(pass.gather(r.point.x, r.point.n, 0).irradiance);
  run.report = rad::compare_to_reference(reference, values);
  return run;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string data = std::string(RAD_SOURCE_DIR) + "/data/";
  const double default_size = rad::SolverSettings{}.patch_size;
  rad::LineChart chart;
  chart.title = "The global solution against the path-traced reference";
  chart.x_label = "solve seconds (2 cores)";
  chart.y_label = "relative error at the points (%)";
  chart.log_x = true;
  chart.log_y = true;
  for (const std::string name : {"cornell-box", "room-window"}) {
    const rad::Scene scene = rad::load_scene(data + name + "/scene.json");
    const std::vector<rad::ReferencePoint> reference = rad::read_reference(
        data + name + "/accuracy-points.csv", data + name + "/accuracy-reference.csv");
    std::vector<Run> runs;
    for (const double size : {0.16, 0.12, 0.08, 0.06, 0.05})
      runs.push_back(measure(scene, reference, size, size == default_size ? 3 : 1));
    double worst_se = 0;
    for (const rad::ReferencePoint& r : reference)
      worst_se = std::max(worst_se, r.standard_error.cwiseQuotient(r.value).maxCoeff());
    std::printf("\n## %s (%zu points; the reference's relative standard errors at most %.3f%%)\n\n",
                name.c_str(), reference.size(), 100 * worst_se);
    std::printf(
        "| patch size | patches | elements | shots | solve seconds | RMS error | largest error "
        "(point) | mean error (bias) | reference's SE of the mean | points' SE of the mean |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
    rad::ChartSeries rms{name + ", RMS", {}, {}}, largest{name + ", largest", {}, {}};
    for (const Run& r : runs) {
      std::printf(
          "| %.2f%s | %d | %d | %d | %.1f%s | %.2f%% | %.2f%% (%d) | %+.3f%% | %.3f%% | %.3f%% |\n",
          r.patch_size, r.patch_size == default_size ? " (default)" : "", r.stats.patches,
          r.stats.elements, r.stats.shots, r.seconds,
          r.patch_size == default_size ? " (median of 3)" : "", 100 * r.report.rms,
          100 * r.report.largest, r.report.worst, 100 * r.report.mean,
          100 * r.report.mean_standard_error, 100 * r.report.points_standard_error);
      rms.x.push_back(r.seconds);
      rms.y.push_back(100 * r.report.rms);
      largest.x.push_back(r.seconds);
      largest.y.push_back(100 * r.report.largest);
      std::fflush(stdout);
    }
    chart.series.push_back(rms);
    chart.series.push_back(largest);
    // The points at the default settings, worst first.
    const Run& d = *std::find_if(runs.begin(), runs.end(),
                                 [&](const Run& r) { return r.patch_size == default_size; });
    std::vector<size_t> order(reference.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    const auto size_of = [&](size_t i) { return d.report.point_errors[i].cwiseAbs().maxCoeff(); };
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return size_of(a) > size_of(b); });
    std::printf("\nAt the default settings, every point (worst first): error in R, G, B.\n\n");
    std::printf("| point | where | R | G | B |\n|---|---|---|---|---|\n");
    for (const size_t i : order) {
      const rad::Rgb& e = d.report.point_errors[i];
      std::printf("| %zu | %s | %+.2f%% | %+.2f%% | %+.2f%% |\n", i, reference[i].label.c_str(),
                  100 * e[0], 100 * e[1], 100 * e[2]);
    }
  }
  if (argc > 1) rad::write_chart_png(argv[1], chart);
  return 0;
}
