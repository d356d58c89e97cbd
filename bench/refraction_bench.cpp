// The refraction heuristic of paper 000 §4 against the path tracer (issue 19): on the scenes of
// data/refraction/ (a glass block, a dispersive prism, a wide pane, a flat and a rippled pool, each
// under the lamp of a black room, so that only the lamp's light reaches the floor points), Fresnel
// off and on, the local pass (vertex tracing of the polygons' emission, tolerance 0) at several
// settings of the accuracy knob (--refraction-tolerance) against two converged references:
//  - the heuristic's model: the path tracer dropping what interfaces reflect, at the same depth
//    (2 crossings): the knob's error, which should fall as it tightens;
//  - the physics: every Fresnel and total internal reflection followed, 8 crossings deep: what
//    the model leaves out besides.
// The first row of each table is the same scene with refraction off (its objects opaque,
// --refraction-depth 0): the cost of refraction is read against it.
// Errors: RMS over the points and channels of (value - reference) / the reference's mean over
// the points, in %. Seconds: the median of repeated runs (at least 3, or as many as fit in a
// second; once from 10 s), since one run of the plain heuristic takes milliseconds on a noisy
// machine. Prints Markdown tables (bench/refraction.sh writes them to
// bench/results/refraction.md) and draws the error against the knob and against time.
// Usage: refraction_bench [KNOB_CHART.png COST_CHART.png] [PATHS]
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "bench/heuristic_measures.h"
#include "formats/points_csv.h"
#include "localpass/local_pass.h"
#include "reference/path_tracer.h"
#include "scene/polygon_faces.h"
#include "scene/scene_loader.h"
#include "viz/charts.h"

using rad::bench::median_seconds;
using rad::bench::rms_error;

int main(int argc, char** argv) {
  const std::string data = std::string(RAD_SOURCE_DIR) + "/data/refraction/";
  const int paths = argc > 3 ? std::atoi(argv[3]) : 400000;
  const double inf = std::numeric_limits<double>::infinity();
  const double opaque = -1;  // a row of the table: refraction off
  const std::vector<double> knobs{opaque, inf, 1, 0.5, 0.2, 0.1, 0.05};
  rad::LineChart knob_chart, cost_chart;
  knob_chart.title = "Refraction heuristic: error against the knob";
  knob_chart.x_label = "--refraction-tolerance (the plain heuristic drawn at 2)";
  knob_chart.y_label = "RMS error against the model's path tracer (% of the mean)";
  knob_chart.log_x = knob_chart.log_y = true;
  knob_chart.legend = rad::LineChart::Corner::bottom_right;
  cost_chart.title = "Refraction heuristic: error against time";
  cost_chart.x_label = "seconds for the points (2 cores)";
  cost_chart.y_label = knob_chart.y_label;
  cost_chart.log_x = cost_chart.log_y = true;
  std::printf("References: %d paths a point (the path tracer of the scene itself).\n", paths);
  for (const std::string name : {"block", "prism", "pane", "water-flat", "water-rippled"}) {
    for (const bool fresnel : {false, true}) {
      rad::Scene scene = rad::load_scene(data + name + ".json");
      for (rad::Material& m : scene.materials) {
        if (m.refracts()) m.refraction->fresnel = fresnel;
      }
      const std::vector<rad::ProbePoint> points = rad::read_points_csv(data + name + "-points.csv");
      const rad::bench::Reference model =
          rad::bench::trace_reference(rad::PathTracer(scene, false), points, paths);
      rad::Scene deep = scene;
      deep.refraction_depth = 8;
      const rad::bench::Reference physics =
          rad::bench::trace_reference(rad::PathTracer(deep, true), points, paths);
      const std::string label = name + (fresnel ? ", Fresnel" : "");
      std::printf("\n## %s (%zu floor points; the model reference's standard error %.2f%%)\n\n",
                  label.c_str(), points.size(), model.noise);
      std::printf(
          "| --refraction-tolerance | seconds | x opaque | images gathered | RMS error vs the "
          "model "
          "(%%) | RMS error vs the physics (%%) |\n|---|---|---|---|---|---|\n");
      rad::ChartSeries knob_series{label, {}, {}}, cost_series{label, {}, {}};
      double opaque_seconds = 0;
      for (const double knob : knobs) {
        rad::LocalPassSettings settings;
        if (knob == opaque)
          settings.refraction_depth = 0;
        else
          settings.refraction_tolerance = knob;
        settings.refraction_max_pieces = 256;
        const rad::LocalPass pass(scene, rad::faces_from_polygons(scene), rad::Method::vertex,
                                  settings);
        std::vector<rad::Rgb> value(points.size());
        std::vector<int> images(points.size());
        const double seconds = median_seconds([&] {
          tbb::parallel_for(size_t(0), points.size(), [&](size_t i) {
            const rad::LocalPassResult r = pass.gather(points[i].x, points[i].n, 0);
            value[i] = r.irradiance + r.refracted;
            images[i] = r.refracted_images;
          });
        });
        if (knob == opaque) opaque_seconds = seconds;
        long total_images = 0;
        for (const int n : images) total_images += n;
        const double error = rms_error(value, model.value);
        const std::string row = knob == opaque        ? "opaque (refraction off)"
                                : std::isfinite(knob) ? std::to_string(knob).substr(0, 4)
                                                      : "none (the paper)";
        std::printf("| %s | %.3g | %.3g | %ld | %.2f | %.2f |\n", row.c_str(), seconds,
                    seconds / opaque_seconds, total_images, error, rms_error(value, physics.value));
        if (knob == opaque) continue;  // not a setting of the knob: no point on the charts
        knob_series.x.push_back(std::isfinite(knob) ? knob : 2.0);
        knob_series.y.push_back(error);
        cost_series.x.push_back(seconds);
        cost_series.y.push_back(error);
      }
      knob_chart.series.push_back(knob_series);
      cost_chart.series.push_back(cost_series);
    }
  }
  if (argc > 2) {
    rad::write_chart_png(argv[1], knob_chart);
    rad::write_chart_png(argv[2], cost_chart);
  }
  return 0;
}
