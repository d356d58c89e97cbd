// Where a point's error against the path tracer comes from (issue 18): cosine-weighted rays
// from the point; at each surface y they meet, the solution's element value B_sol(y) and the
// path-traced radiosity B(y) = E + rho H(y) at the same y (paired samples, so their difference
// has far less noise than either). H(x) = pi x the mean of B over the rays, so each bin's sum of
// B_sol - B over the number of rays is its share of the point's error. Binned by polygon and by
// the distance from x to y (the elements seen from close by are where a concave edge's error
// lives). One line per bin: polygon, distance bin, rays, mean B_sol and B per channel, and the
// bin's share of the error in % of H per channel.
// Usage: radiosity_profile SCENE SOLUTION X Y Z NX NY NZ [RAYS=400000] [PATHS=8]
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "formats/solution_io.h"
#include "radiosity/solution.h"
#include "reference/path_tracer.h"
#include "scene/polygon.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"

namespace {

using rad::Rgb;
using rad::Vec3;

constexpr std::array<double, 6> kBinEnds = {1, 2, 5, 20, 80, 1e300};  // distance bins, scene units

/// True when y (in the element's plane, normal n) lies in its outline or on its boundary.
bool inside(const rad::Element& el, const Vec3& y, const Vec3& n) {
  const rad::PlaneFrame frame(el.corners.front(), n);  // project_to_plane's frame
  return rad::contains_2d(rad::project_to_plane(el.corners, n), frame.to_2d(y));
}

struct Bin {
  Rgb solution = Rgb::Zero(), traced = Rgb::Zero();
  long rays = 0;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 9) {
    std::fprintf(stderr, "usage: radiosity_profile SCENE SOLUTION X Y Z NX NY NZ [RAYS] [PATHS]\n");
    return 2;
  }
  const rad::Scene scene = rad::load_scene(argv[1]);
  const rad::Solution solution = rad::read_solution(argv[2]);
  const Vec3 x(std::stod(argv[3]), std::stod(argv[4]), std::stod(argv[5]));
  const Vec3 n = Vec3(std::stod(argv[6]), std::stod(argv[7]), std::stod(argv[8])).normalized();
  const int chunks = (argc > 9 ? std::stoi(argv[9]) : 400000) / 1000;
  const int paths = argc > 10 ? std::stoi(argv[10]) : 8;
  const rad::RayCaster caster(scene);
  const rad::PathTracer tracer(scene);
  std::vector<std::vector<int>> leaves_of(scene.polygons.size());
  for (const int e : solution.leaves()) leaves_of[solution.elements[e].polygon].push_back(e);
  const rad::PlaneFrame frame(x, n);
  const double offset = 1e-7 * scene.bounds().diagonal();
  std::map<std::pair<int, int>, Bin> bins;
  std::mutex lock;
  tbb::parallel_for(0, chunks, [&](int chunk) {
    std::mt19937_64 rng(chunk + 1);
    std::uniform_real_distribution<double> uniform(0, 1);
    std::map<std::pair<int, int>, Bin> local;
    for (int i = 0; i < 1000; ++i) {
      const double r2 = uniform(rng), phi = 2 * std::numbers::pi * uniform(rng);
      const Vec3 d = frame.cosine_direction(r2, phi);
      const auto hit = caster.closest_hit({x + offset * n, d}, 0);
      if (!hit || !hit->front_facing) continue;  // nothing, or a back: black for both
      const rad::Material& m = scene.materials[scene.polygons[hit->polygon].material];
      const rad::Element* element = nullptr;
      for (const int e : leaves_of[hit->polygon]) {
        if (inside(solution.elements[e], hit->point, hit->normal)) {
          element = &solution.elements[e];
          break;
        }
      }
      if (!element) continue;  // a seam between elements: rare, and left out of both
      const Rgb traced =
          m.emission +
          m.reflectance.cwiseProduct(
              tracer.irradiance(hit->point, hit->normal, paths, chunk * 1000 + i).mean);
      int bin = 0;
      while (hit->distance >= kBinEnds[bin]) ++bin;
      Bin& b = local[{hit->polygon, bin}];
      b.solution += element->radiosity;
      b.traced += traced;
      ++b.rays;
    }
    const std::lock_guard<std::mutex> guard(lock);
    for (const auto& [key, b] : local) {
      Bin& into = bins[key];
      into.solution += b.solution;
      into.traced += b.traced;
      into.rays += b.rays;
    }
  });
  const double rays = 1000.0 * chunks;
  Rgb solution_h = Rgb::Zero(), traced_h = Rgb::Zero();
  for (const auto& [key, b] : bins) solution_h += b.solution, traced_h += b.traced;
  solution_h *= std::numbers::pi / rays;
  traced_h *= std::numbers::pi / rays;
  std::printf("H from the solution's elements (%g rays): %.6g %.6g %.6g\n", rays, solution_h[0],
              solution_h[1], solution_h[2]);
  std::printf("H path-traced at the same points (%d paths each): %.6g %.6g %.6g\n", paths,
              traced_h[0], traced_h[1], traced_h[2]);
  std::printf(
      "polygon,distance_to,rays,B_sol_r,B_sol_g,B_sol_b,B_r,B_g,B_b,share_r,share_g,share_b\n");
  for (const auto& [key, b] : bins) {
    const Rgb share = (b.solution - b.traced) * (std::numbers::pi / rays);
    std::printf("%d,%g,%ld", key.first, kBinEnds[key.second], b.rays);
    for (int c = 0; c < 3; ++c) std::printf(",%.5g", b.solution[c] / b.rays);
    for (int c = 0; c < 3; ++c) std::printf(",%.5g", b.traced[c] / b.rays);
    for (int c = 0; c < 3; ++c) std::printf(",%+.3f%%", 100 * share[c] / traced_h[c]);
    std::printf("\n");
  }
}
