// The two exact gatherers side by side: (1) the Cornell box meshed into patches, every patch
// emitting (the local pass, where patches of a solution radiate their radiosity), at several
// mesh sizes, one thread and two; (2) the stress scene of paper 001 Fig. 7b: ~1000 thin
// triangles under a large crescent-shaped source (direct light). Prints Markdown tables.
// Usage: hemisphere_bench [POINTS]
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "hemisphere/hemisphere_gatherer.h"
#include "radiosity/mesher.h"
#include "radiosity/solution_faces.h"
#include "scene/polygon.h"
#include "scene/polygon_faces.h"
#include "scene/scene_loader.h"
#include "vertex/vertex_tracer.h"

namespace {

/// The scene's patches as faces of their polygons, every one emitting 1.
std::vector<rad::EmittingFace> patch_faces(const rad::Scene& scene, double patch_size) {
  rad::Solution solution;
  for (const rad::Patch& p : rad::make_patches(scene, patch_size * scene.bounds().diagonal())) {
    rad::Element e;
    e.polygon = p.polygon;
    e.corners = p.corners;
    e.radiosity = rad::Rgb::Ones();
    solution.elements.push_back(std::move(e));
  }
  return rad::faces_from_solution(scene, solution);
}

/// Paper 001 Fig. 7b: `count` thin triangles between a floor and a crescent-shaped source.
rad::Scene stress_scene(int count) {
  rad::Scene s;
  s.materials.push_back(rad::Material{"grey", rad::Rgb::Constant(0.5), rad::Rgb::Zero()});
  s.materials.push_back(rad::Material{"lamp", rad::Rgb::Zero(), rad::Rgb::Ones()});
  const auto add = [&](std::vector<rad::Vec3> v, int material) {
    rad::Polygon p;
    p.vertices = std::move(v);
    p.normal = rad::newell_vector(p.vertices).normalized();
    p.material = material;
    s.polygons.push_back(std::move(p));
  };
  add({{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}}, 0);
  // The crescent: the disk of radius 1.5 minus the disk of radius 1.2 centred at (0.6, 0); the
  // circles cross at (0.975, +-1.140). Outer arc counter-clockwise through (-1.5, 0), inner arc
  // back clockwise through (-0.6, 0), then reversed so that it faces the floor.
  std::vector<rad::Vec3> crescent;
  const int n = 48;
  const double outer = std::atan2(1.140, 0.975), inner = std::atan2(1.140, 0.375);
  for (int i = 0; i <= n; ++i) {
    const double a = outer + (2 * M_PI - 2 * outer) * i / n;
    crescent.push_back({1.5 * std::cos(a), 1.5 * std::sin(a), 2});
  }
  for (int i = 1; i < n; ++i) {
    const double a = 2 * M_PI - inner - (2 * M_PI - 2 * inner) * i / n;
    crescent.push_back({0.6 + 1.2 * std::cos(a), 1.2 * std::sin(a), 2});
  }
  std::reverse(crescent.begin(), crescent.end());
  add(crescent, 1);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.5, 1.5), z(0.3, 1.5), angle(0, 2 * M_PI);
  for (int i = 0; i < count; ++i) {
    const rad::Vec3 c(u(rng), u(rng), z(rng));
    const double a = angle(rng);
    const rad::Vec3 along(std::cos(a), std::sin(a), 0.1 * u(rng));
    const rad::Vec3 across(-std::sin(a), std::cos(a), 0);
    add({c - 0.4 * along, c + 0.4 * along, c + 0.01 * across}, 0);
  }
  s.objects.push_back(rad::SceneObject{"", "", 0, 0, static_cast<int>(s.polygons.size())});
  return s;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

int main(int argc, char** argv) {
  const int count = argc > 1 ? std::stoi(argv[1]) : 400;
  const rad::Scene cornell =
      rad::load_scene(std::string(RAD_SOURCE_DIR) + "/data/cornell-box/scene.json");
  // Seeded points on the room's surfaces (floor, ceiling, walls), with their normals.
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.02, 0.98);
  std::vector<std::pair<rad::Vec3, rad::Vec3>> points;
  for (int i = 0; i < count; ++i) {
    switch (i % 4) {
      case 0:
        points.push_back({{556 * u(rng), 0, 559.2 * u(rng)}, {0, 1, 0}});
        break;  // floor
      case 1:
        points.push_back({{549.6 * u(rng), 548.8 * u(rng), 559.2}, {0, 0, -1}});
        break;  // back
      case 2:
        points.push_back({{0, 548.8 * u(rng), 559.2 * u(rng)}, {1, 0, 0}});
        break;  // right
      default:
        points.push_back({{556 * u(rng), 548.8, 559.2 * u(rng)}, {0, -1, 0}});
        break;  // ceiling
    }
  }
  std::printf(
      "| patch size (of diagonal) | patches (all emitting) | method | points/s, 1 thread | "
      "points/s, 2 threads | ms per point, 1 thread |\n");
  std::printf("|---|---|---|---|---|---|\n");
  const auto rate = [&](const auto& gather, int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const auto start = std::chrono::steady_clock::now();
    tbb::parallel_for(size_t(0), points.size(),
                      [&](size_t i) { gather(points[i].first, points[i].second); });
    return points.size() / seconds_since(start);
  };
  for (const double size : {0.062, 0.034, 0.0185}) {
    const auto faces = patch_faces(cornell, size);
    const rad::HemisphereGatherer hemisphere(faces, cornell.tolerance());
    const rad::VertexTracer tracer(cornell, faces);
    const auto by_hemisphere = [&](const rad::Vec3& x, const rad::Vec3& n) {
      return hemisphere.gather(x, n).irradiance;
    };
    const auto by_vertex = [&](const rad::Vec3& x, const rad::Vec3& n) {
      return tracer.gather(x, n).irradiance;
    };
    const double h1 = rate(by_hemisphere, 1), h2 = rate(by_hemisphere, 2);
    std::printf("| %.4f | %zu | hemisphere | %.0f | %.0f | %.2f |\n", size, faces.size(), h1, h2,
                1000 / h1);
    const double v1 = rate(by_vertex, 1), v2 = rate(by_vertex, 2);
    std::printf("| %.4f | %zu | vertex | %.0f | %.0f | %.2f |\n", size, faces.size(), v1, v2,
                1000 / v1);
    std::fflush(stdout);
  }

  // The stress scene: points on the floor under the source, one thread.
  const rad::Scene stress = stress_scene(1000);
  points.clear();
  std::uniform_real_distribution<double> floor(-1.2, 1.2);
  for (int i = 0; i < count / 4; ++i) points.push_back({{floor(rng), floor(rng), 0}, {0, 0, 1}});
  const rad::HemisphereGatherer hemisphere(rad::faces_from_polygons(stress), stress.tolerance());
  const rad::VertexTracer tracer(stress);
  const double h1 = rate(
      [&](const rad::Vec3& x, const rad::Vec3& n) { return hemisphere.gather(x, n).irradiance; },
      1);
  const double v1 = rate(
      [&](const rad::Vec3& x, const rad::Vec3& n) { return tracer.gather(x, n).irradiance; }, 1);
  double worst = 0, lit = 0;
  for (const auto& [x, n] : points) {
    const double a = hemisphere.gather(x, n).irradiance.x(), b = tracer.gather(x, n).irradiance.x();
    worst = std::max(worst, std::abs(a - b) / std::max(a, 1e-300));
    lit += a / points.size();
  }
  std::printf(
      "\n| stress scene (001 Fig. 7b) | polygons | method | ms per point, 1 thread "
      "|\n|---|---|---|---|\n");
  std::printf(
      "| 1000 thin triangles, crescent source, %zu floor points | %zu | hemisphere | %.2f |\n",
      points.size(), stress.polygons.size(), 1000 / h1);
  std::printf(
      "| (mean irradiance %.3g; largest relative difference between the methods %.1e) | %zu | "
      "vertex | %.2f |\n",
      lit, worst, stress.polygons.size(), 1000 / v1);
  return 0;
}
