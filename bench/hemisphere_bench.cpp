// Exact hemisphere gather on the Cornell box meshed into patches, every patch emitting (the
// situation of the local pass, where patches of a solution radiate their radiosity): points
// per second at several mesh sizes, one thread and all threads. Prints a Markdown table.
// Usage: hemisphere_bench [POINTS]
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cstdio>
#include <random>
#include <string>

#include "localpass/hemisphere_gather.h"
#include "radiosity/mesher.h"
#include "scene/scene_loader.h"

namespace {

/// The scene with every polygon replaced by its patches, each a polygon of its own.
rad::Scene patch_scene(const rad::Scene& scene, double patch_size) {
  rad::Scene out;
  out.materials = scene.materials;
  out.objects = scene.objects;
  for (const rad::Patch& p : rad::make_patches(scene, patch_size * scene.bounds().diagonal())) {
    rad::Polygon polygon = scene.polygons[p.polygon];
    polygon.vertices = p.corners;
    polygon.area = p.area;
    out.polygons.push_back(std::move(polygon));
  }
  return out;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

int main(int argc, char** argv) {
  const int count = argc > 1 ? std::stoi(argv[1]) : 400;
  const rad::Scene cornell = rad::load_scene(std::string(RAD_SOURCE_DIR) + "/data/cornell-box/scene.json");
  // Seeded points on the room's surfaces (floor, ceiling, walls), with their normals.
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.02, 0.98);
  std::vector<std::pair<rad::Vec3, rad::Vec3>> points;
  for (int i = 0; i < count; ++i) {
    switch (i % 4) {
      case 0: points.push_back({{556 * u(rng), 0, 559.2 * u(rng)}, {0, 1, 0}}); break;           // floor
      case 1: points.push_back({{549.6 * u(rng), 548.8 * u(rng), 559.2}, {0, 0, -1}}); break;  // back
      case 2: points.push_back({{0, 548.8 * u(rng), 559.2 * u(rng)}, {1, 0, 0}}); break;       // right
      default: points.push_back({{556 * u(rng), 548.8, 559.2 * u(rng)}, {0, -1, 0}}); break;   // ceiling
    }
  }
  std::printf("| patch size (of diagonal) | patches (all emitting) | points/s, 1 thread | points/s, 2 threads | ms per point, 1 thread |\n");
  std::printf("|---|---|---|---|---|\n");
  for (const double size : {0.062, 0.034, 0.0185}) {
    const rad::Scene scene = patch_scene(cornell, size);
    std::vector<rad::Rgb> exitance(scene.polygons.size(), rad::Rgb::Ones());
    const rad::HemisphereGatherer gatherer(scene, exitance);
    double rate[2];
    for (int threads : {1, 2}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      const auto start = std::chrono::steady_clock::now();
      tbb::parallel_for(size_t(0), points.size(), [&](size_t i) { gatherer.gather(points[i].first, points[i].second); });
      rate[threads - 1] = points.size() / seconds_since(start);
    }
    std::printf("| %.4f | %zu | %.0f | %.0f | %.2f |\n", size, scene.polygons.size(), rate[0], rate[1], 1000 / rate[0]);
    std::fflush(stdout);
  }
  return 0;
}
