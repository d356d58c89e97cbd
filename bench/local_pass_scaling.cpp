// How the local pass's cost per pixel grows with the solution's element count (issue 15's
// scaling target: no faster than elements^0.5 at tolerance 0.01). The same Cornell box meshed
// uniformly at several patch sizes (no refinement, so the element count is the only change),
// the camera's view at SIZE x SIZE, one thread; the exponent is the least-squares slope of
// log(us per pixel) against log(elements). Prints a Markdown table.
// Usage: local_pass_scaling [SIZE] [TOLERANCE] [METHOD]   (defaults 64 0.01 hemisphere)
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "localpass/local_pass.h"
#include "radiosity/solution_faces.h"
#include "radiosity/solver.h"
#include "scene/camera.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"

int main(int argc, char** argv) {
  using Clock = std::chrono::steady_clock;
  const int size = argc > 1 ? std::stoi(argv[1]) : 64;
  const double tolerance = argc > 2 ? std::stod(argv[2]) : 0.01;
  const rad::Method method = *rad::parse_method(argc > 3 ? argv[3] : "hemisphere");
  const rad::Scene scene =
      rad::load_scene(std::string(RAD_SOURCE_DIR) + "/data/cornell-box/scene.json");
  const rad::RayCaster caster(scene);
  rad::CameraSpec spec = *scene.camera;
  spec.width = spec.height = size;
  const rad::Camera camera(spec);
  // The visible points once: the same pixels for every mesh.
  struct Point {
    rad::Vec3 x, n;
  };
  std::vector<Point> points;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const auto hit = caster.closest_hit(camera.ray(x + 0.5, y + 0.5));
      if (hit && hit->front_facing) points.push_back({hit->point, hit->normal});
    }

  std::printf(
      "| patch size | elements | solve seconds (all cores) | us per pixel (one thread) | clusters "
      "per pixel | faces gathered exactly per pixel | projected per pixel |\n"
      "|---|---|---|---|---|---|---|\n");
  std::vector<double> log_elements, log_cost;
  for (const double patch_size : {0.14, 0.07, 0.04, 0.023}) {
    rad::SolverSettings settings;
    settings.patch_size = patch_size;
    settings.refine_threshold = 0;
    settings.refine_passes = 0;
    auto start = Clock::now();
    const rad::Solution solution = rad::solve(caster, settings);
    const double solve_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    const rad::LocalPass pass(scene, rad::faces_from_solution(scene, solution), method);
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    double clusters = 0, exact = 0, projected = 0;
    start = Clock::now();
    for (const Point& p : points) {
      const rad::LocalPassResult r = pass.gather(p.x, p.n, tolerance);
      clusters += r.clusters, exact += r.gathered_exactly, projected += r.projected;
    }
    const double us = 1e6 * std::chrono::duration<double>(Clock::now() - start).count() /
                      static_cast<double>(points.size());
    const double n = static_cast<double>(points.size());
    std::printf("| %.3f | %d | %.1f | %.0f | %.0f | %.1f | %.0f |\n", patch_size, pass.face_count(),
                solve_seconds, us, clusters / n, exact / n, projected / n);
    std::fflush(stdout);
    log_elements.push_back(std::log(pass.face_count()));
    log_cost.push_back(std::log(us));
  }
  // Least-squares slope of log cost against log elements.
  double mx = 0, my = 0;
  for (size_t i = 0; i < log_cost.size(); ++i) mx += log_elements[i], my += log_cost[i];
  mx /= log_cost.size(), my /= log_cost.size();
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < log_cost.size(); ++i) {
    sxy += (log_elements[i] - mx) * (log_cost[i] - my);
    sxx += (log_elements[i] - mx) * (log_elements[i] - mx);
  }
  std::printf(
      "\nFitted exponent (cost per pixel ~ elements^k): k = %.2f (%s, tolerance %g, %zu "
      "pixels)\n",
      sxy / sxx, rad::method_name(method).c_str(), tolerance, points.size());
  return 0;
}
