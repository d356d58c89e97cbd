#include "radiosity/hierarchical_solver.h"

#include <chrono>
#include <string>

#include "radiosity/hierarchical_state.h"
#include "scene/error.h"

namespace rad {

std::string hierarchical_unsupported(const Scene& scene) {
  for (const Polygon& p : scene.polygons) {
    const Material& m = scene.materials[p.material];
    if (m.is_filter()) return "filters (transmitting materials)";
    if (m.refracts()) return "refracting objects";
    if (m.is_mirror()) return "mirrors and glossy surfaces";
  }
  return {};
}

/// At most this many times the sweeps converge again after opening what linking left out.
constexpr int kOpeningRounds = 16;

Solution solve_hierarchical(const RayCaster& caster, const SolverSettings& settings,
                            const std::function<void(const SolveProgress&)>& progress) {
  settings.validate();
  if (const std::string missing = hierarchical_unsupported(caster.scene()); !missing.empty())
    throw Error("the hierarchical solver does not carry " + missing + " yet");
  const auto start = std::chrono::steady_clock::now();
  HierarchicalSolver solver(caster, settings, progress);
  // Sweeps until converged, then until no link linking left out has become bright enough to
  // be opened (light reaches the surfaces that were dark at first bounce by bounce).
  SolveStats::Steps steps;
  const auto timed = [](double& seconds, const auto& step) {
    const auto begin = std::chrono::steady_clock::now();
    step();
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  };
  const auto converge = [&] {
    timed(steps.sweeping, [&] { solver.iterate(); });
    for (int round = 0; round < kOpeningRounds; ++round) {
      int opened = 0;
      timed(steps.opening, [&] { opened = solver.open_deferred(); });
      if (opened == 0) break;
      timed(steps.sweeping, [&] { solver.iterate(); });
    }
  };
  timed(steps.linking, [&] { solver.link(); });
  converge();
  for (int pass = 0; pass < settings.refine_passes; ++pass) {
    int split = 0;
    timed(steps.refining, [&] { split = solver.refine(); });
    if (split == 0) break;
    converge();
  }
  Solution solution = solver.finish(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  solution.stats.steps = steps;
  return solution;
}

}  // namespace rad
