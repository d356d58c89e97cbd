// Progressive radiosity on the Cornell box at three patch sizes: solve time, patches,
// elements, shots. Prints a Markdown table (bench/run_all.sh writes it to bench/results/).
// Usage: solve_bench [SCENE]
#include <cstdio>
#include <string>

#include "radiosity/solver.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"

int main(int argc, char** argv) {
  const std::string path =
      argc > 1 ? argv[1] : std::string(RAD_SOURCE_DIR) + "/data/cornell-box/scene.json";
  const rad::Scene scene = rad::load_scene(path);
  const rad::RayCaster caster(scene);
  std::printf(
      "| patch size (of diagonal) | patches | elements (leaves) | split | shots | unshot | solve "
      "seconds | seconds / default |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  double default_seconds = 0;
  for (const double size : {0.08, 0.12, 0.05}) {  // the default first, for the ratio column
    rad::SolverSettings settings;
    settings.patch_size = size;
    const rad::Solution s = rad::solve(caster, settings);
    if (size == 0.08) default_seconds = s.stats.seconds;
    std::printf("| %.2f%s | %d | %d | %d | %d | %.4f%% | %.1f | %.2f |\n", size,
                size == 0.08 ? " (default)" : "", s.stats.patches, s.stats.elements,
                s.stats.refined, s.stats.shots, 100 * s.stats.unshot_fraction, s.stats.seconds,
                s.stats.seconds / default_seconds);
    std::fflush(stdout);
  }
  return 0;
}
