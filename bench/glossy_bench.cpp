// Glossy transfer by backward beams (paper 003) against the path tracer (issue 20):
//  1. accuracy: on data/glossy-ring/ with a black floor and rim (so that what reaches the floor
//     points is the light straight and by way of the ring), the local pass's glossy part plus
//     the exact direct light against the path tracer of the scene itself (which samples the
//     lobes: every glossy bounce), at each lobe spread sigma and --glossy-split;
//     and, lit by a square lamp instead, at each --glossy-light-split;
//  2. cost: seconds per receiver of the glossy gather (121 points on a grid over the floor)
//     against the number of scatterer triangles (rings of 10 to 160 segments, split 8), with
//     the cone hierarchy and without.
// Errors: RMS over the points and channels of (value - reference) / the reference's mean over
// the points, in %. Seconds: medians of repeated runs. Prints Markdown tables (bench/glossy.sh
// writes them to bench/results/glossy.md) and draws the two charts.
// Usage: glossy_bench [SIGMA_CHART.png COST_CHART.png] [PATHS]
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "bench/heuristic_measures.h"
#include "formats/points_csv.h"
#include "localpass/local_pass.h"
#include "reference/path_tracer.h"
#include "scene/polygon_faces.h"
#include "scene/polygon_validation.h"
#include "scene/scene_loader.h"
#include "specular/glossy_transfer.h"
#include "viz/charts.h"

using rad::bench::median_seconds;
using rad::bench::rms_error;

namespace {

/// The ring of data/glossy-ring/ with `segments` quads inside (smooth), on a black floor, lit
/// by the point light, or (with `lamp`) by a square lamp of side 0.5 in its place facing the
/// ring, of the same power toward it.
rad::Scene ring(int segments, double sigma, bool lamp = false) {
  rad::Scene scene;
  scene.materials.push_back({"floor", rad::Rgb::Zero(), rad::Rgb::Zero()});
  rad::Material gold{"gold", rad::Rgb::Zero(), rad::Rgb::Zero(), rad::Rgb::Zero(),
                     rad::Rgb(0.9, 0.75, 0.4)};
  gold.gloss = sigma;
  scene.materials.push_back(gold);
  std::vector<std::string> warnings;
  const auto add = [&](std::vector<rad::Vec3> v, int material, int object) {
    for (rad::Polygon& p : rad::make_polygons(std::move(v), "ring", material, object, 0, warnings))
      scene.polygons.push_back(std::move(p));
  };
  add({{-2.5, -2.5, 0}, {2.5, -2.5, 0}, {2.5, 2.5, 0}, {-2.5, 2.5, 0}}, 0, 0);
  const double r = 1, h = 0.45;
  for (int k = 0; k < segments; ++k) {
    const double a = 2 * std::numbers::pi * k / segments,
                 b = 2 * std::numbers::pi * (k + 1) / segments;
    const rad::Vec3 p0(r * std::cos(a), r * std::sin(a), 0),
        p1(r * std::cos(b), r * std::sin(b), 0);
    add({p0, p0 + rad::Vec3(0, 0, h), p1 + rad::Vec3(0, 0, h), p1}, 1, 1);
    rad::Polygon& q = scene.polygons.back();
    q.vertex_normals.clear();
    for (const rad::Vec3& v : q.vertices)
      q.vertex_normals.push_back(-rad::Vec3(v.x(), v.y(), 0).normalized());
  }
  scene.objects = {{"floor", "", 0, 0, 1}, {"ring", "", 1, 1, segments}};
  const rad::Vec3 light(-2.2, 0, 1.1);
  if (!lamp) {
    scene.lights.push_back({light, rad::Rgb::Constant(6)});
    return scene;
  }
  // Facing the ring's centre; exitance M with M A / pi = 6 W/sr along its normal.
  const double side = 0.5;
  const rad::Vec3 w = (rad::Vec3(0, 0, 0.2) - light).normalized();
  const rad::Vec3 u = w.cross(rad::Vec3::UnitY()).normalized(), v = w.cross(u);
  scene.materials.push_back(
      {"lamp", rad::Rgb::Zero(), rad::Rgb::Constant(6 * std::numbers::pi / (side * side))});
  const double half = side / 2;
  add({light + half * (-u - v), light + half * (-u + v), light + half * (u + v),
       light + half * (u - v)},
      2, 2);
  if (scene.polygons.back().normal.dot(w) < 0) {
    std::reverse(scene.polygons.back().vertices.begin(), scene.polygons.back().vertices.end());
    scene.polygons.back().normal = -scene.polygons.back().normal;
  }
  scene.objects.push_back({"lamp", "", 2, static_cast<int>(scene.polygons.size()) - 1, 1});
  return scene;
}

/// The local pass at the points (tolerance 0): the exact direct light plus the glossy beams.
std::vector<rad::Rgb> with_beams(const rad::Scene& scene,
                                 const std::vector<rad::ProbePoint>& points,
                                 const rad::GlossySettings& glossy) {
  rad::LocalPassSettings settings;
  settings.glossy = glossy;
  const rad::LocalPass pass(scene, rad::faces_from_polygons(scene), rad::Method::vertex, settings);
  std::vector<rad::Rgb> value(points.size());
  tbb::parallel_for(size_t(0), points.size(), [&](size_t i) {
    const rad::LocalPassResult r = pass.gather(points[i].x, points[i].n, 0);
    value[i] = r.irradiance + r.glossy;
  });
  return value;
}

}  // namespace

int main(int argc, char** argv) {
  const int paths = argc > 3 ? std::atoi(argv[3]) : 400000;
  const std::vector<rad::ProbePoint> points =
      rad::read_points_csv(std::string(RAD_SOURCE_DIR) + "/data/glossy-ring/ring-points.csv");
  rad::LineChart sigma_chart, cost_chart;
  sigma_chart.title = "Glossy beams: error against the lobe's spread";
  sigma_chart.x_label = "gloss sigma (radians)";
  sigma_chart.y_label = "RMS error against the path tracer (% of the mean)";
  sigma_chart.log_x = sigma_chart.log_y = true;
  cost_chart.title = "Glossy beams: time per receiver against scatterer triangles";
  cost_chart.x_label = "scatterer triangles (ring segments x 2)";
  cost_chart.y_label = "microseconds per receiver (2 cores)";
  cost_chart.log_x = cost_chart.log_y = true;
  cost_chart.legend = rad::LineChart::Corner::top_left;

  const std::vector<double> sigmas{0.02, 0.05, 0.1, 0.2, 0.4};
  const std::vector<int> splits{1, 2, 4, 8, 16};
  std::printf("## Accuracy: the ring of 40 segments, %zu floor points, %d paths a point\n\n",
              points.size(), paths);
  std::printf("| sigma | reference's standard error (%%) |");
  for (const int s : splits) std::printf(" split %d (%%) |", s);
  std::printf("\n|---|---|");
  for (size_t i = 0; i < splits.size(); ++i) std::printf("---|");
  std::printf("\n");
  std::vector<rad::ChartSeries> by_split(splits.size());
  for (size_t i = 0; i < splits.size(); ++i)
    by_split[i].name = "--glossy-split " + std::to_string(splits[i]);
  for (const double sigma : sigmas) {
    const rad::Scene scene = ring(40, sigma);
    const rad::bench::Reference reference =
        rad::bench::trace_reference(rad::PathTracer(scene), points, paths);
    std::printf("| %g | %.2f |", sigma, reference.noise);
    for (size_t k = 0; k < splits.size(); ++k) {
      rad::GlossySettings settings;
      settings.split = splits[k];
      const double error = rms_error(with_beams(scene, points, settings), reference.value);
      std::printf(" %.2f |", error);
      by_split[k].x.push_back(sigma);
      by_split[k].y.push_back(error);
    }
    std::printf("\n");
  }
  sigma_chart.series = by_split;

  std::printf(
      "\n## Accuracy against the lamp's split: a square lamp of side 0.5 in the light's place, "
      "sigma 0.1, split 8\n\n| --glossy-light-split | point sources | RMS error (%%) |\n"
      "|---|---|---|\n");
  {
    const rad::Scene scene = ring(40, 0.1, true);
    const rad::bench::Reference reference =
        rad::bench::trace_reference(rad::PathTracer(scene), points, paths);
    for (const int light_split : {1, 2, 4, 8}) {
      rad::GlossySettings settings;
      settings.light_split = light_split;
      std::printf("| %d | %d | %.2f |\n", light_split, 2 * light_split * light_split,
                  rms_error(with_beams(scene, points, settings), reference.value));
    }
    std::printf("\nThe reference's own standard error: %.2f%%.\n", reference.noise);
  }

  std::printf(
      "\n## Cost: the glossy gather at 121 points on a grid over the floor, sigma 0.08, split 8 "
      "(64 pieces a triangle)\n\n| scatterer triangles | beams | beams visited per receiver | "
      "microseconds per receiver, hierarchy | without | speed-up |\n|---|---|---|---|---|---|\n");
  rad::ChartSeries with{"cone hierarchy", {}, {}}, without{"every beam", {}, {}};
  // Receivers over the whole floor, as a picture's pixels are (the accuracy points lie in the
  // caustic, where most beams do reach).
  std::vector<rad::ProbePoint> floor;
  for (int i = 0; i <= 10; ++i) {
    for (int j = 0; j <= 10; ++j)
      floor.push_back({rad::Vec3(-2.4 + 0.48 * i, -2.4 + 0.48 * j, 0), rad::Vec3::UnitZ()});
  }
  for (const int segments : {10, 20, 40, 80, 160}) {
    const rad::Scene scene = ring(segments, 0.08);
    rad::GlossySettings cut, plain;
    plain.hierarchy = false;
    const rad::GlossyTransfer fast(scene, cut), slow(scene, plain);
    long visited = 0;
    const auto run = [&](const rad::GlossyTransfer& t, bool count) {
      std::vector<int> beams(floor.size());
      tbb::parallel_for(size_t(0), floor.size(),
                        [&](size_t i) { beams[i] = t.irradiance(floor[i].x, floor[i].n).beams; });
      if (count) {
        visited = 0;
        for (const int b : beams) visited += b;
      }
    };
    const double per = 1e6 / static_cast<double>(floor.size());
    const double fast_us = per * median_seconds([&] { run(fast, true); });
    const double slow_us = per * median_seconds([&] { run(slow, false); });
    const int triangles = 2 * segments;
    std::printf("| %d | %d | %.0f | %.1f | %.1f | %.1f |\n", triangles, fast.beam_count(),
                static_cast<double>(visited) / static_cast<double>(floor.size()), fast_us, slow_us,
                slow_us / fast_us);
    with.x.push_back(triangles), with.y.push_back(fast_us);
    without.x.push_back(triangles), without.y.push_back(slow_us);
  }
  cost_chart.series = {with, without};
  if (argc > 2) {
    rad::write_chart_png(argv[1], sigma_chart);
    rad::write_chart_png(argv[2], cost_chart);
  }
  return 0;
}
