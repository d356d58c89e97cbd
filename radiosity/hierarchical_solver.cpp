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
  const auto converge = [&] {
    solver.iterate();
    for (int round = 0; round < kOpeningRounds && solver.open_deferred() > 0; ++round)
      solver.iterate();
  };
  solver.link();
  converge();
  for (int pass = 0; pass < settings.refine_passes; ++pass) {
    if (solver.refine() == 0) break;
    converge();
  }
  return solver.finish(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace rad
