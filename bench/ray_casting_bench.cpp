// Ray casting throughput on the Cornell box: the cost floor under every per-pixel pass.
//   closest_hit / occluded: one thread, seeded random rays from inside the box.
//   albedo_render: a whole 512 x 512 primary-ray image, all cores (TBB).
#include <benchmark/benchmark.h>

#include <random>

#include "render/albedo_render.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"

namespace {

const rad::Scene& cornell() {
  static const rad::Scene scene =
      rad::load_scene(std::string(RAD_SOURCE_DIR) + "/data/cornell-box/scene.json");
  return scene;
}

std::vector<rad::Ray> random_rays(int n) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g;
  std::vector<rad::Ray> rays;
  for (int i = 0; i < n; ++i) {
    rays.push_back({rad::Vec3(10 + 536 * u(rng), 10 + 528 * u(rng), 10 + 539 * u(rng)),
                    rad::Vec3(g(rng), g(rng), g(rng)).normalized()});
  }
  return rays;
}

void closest_hit(benchmark::State& state) {
  const rad::RayCaster caster(cornell());
  const auto rays = random_rays(4096);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(caster.closest_hit(rays[i++ & 4095]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(closest_hit);

void occluded(benchmark::State& state) {
  const rad::RayCaster caster(cornell());
  const auto rays = random_rays(4096);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(caster.occluded(rays[i++ & 4095], 0, 300));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(occluded);

void albedo_render_512(benchmark::State& state) {
  const rad::RayCaster caster(cornell());
  const rad::Camera camera(*cornell().camera);
  for (auto _ : state) benchmark::DoNotOptimize(rad::render_albedo(caster, camera));
  state.SetItemsProcessed(state.iterations() * 512 * 512);
}
BENCHMARK(albedo_render_512)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
