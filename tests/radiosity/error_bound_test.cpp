// The certified bound on the solve's own error (radiosity/error_bound.h): it contains the error
// where the exact answer is known (the furnace, per channel), and where it is not, the distance
// to a solve of the same discrete system run much further; and it is not vacuous.
#include "radiosity/error_bound.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "radiosity/solver.h"
#include "scene/scene_loader.h"

namespace rad {
namespace {

const std::filesystem::path kScenes = std::filesystem::path(RAD_SOURCE_DIR) / "data";

Solution solve_scene(const Scene& scene, const SolverSettings& settings) {
  const RayCaster caster(scene);
  return solve(caster, settings);
}

/// Per channel, the largest |B - expected| over the leaves.
Rgb largest_error(const Solution& s, const Rgb& expected) {
  Rgb worst = Rgb::Zero();
  for (const int e : s.leaves())
    worst = worst.cwiseMax((s.elements[e].radiosity - expected).cwiseAbs());
  return worst;
}

TEST(ErrorBound, IsTheNeumannSeriesTail) {
  // rho max|U| / (1 - rho) per channel: a half reflects as much again as it receives.
  const Rgb bound = iteration_error_bound(Rgb(1, -2, 4), Rgb(0.5, 0, 0.75));
  EXPECT_DOUBLE_EQ(bound[0], 1);
  EXPECT_DOUBLE_EQ(bound[1], 0);  // nothing reflects: the shot light is all there is
  EXPECT_DOUBLE_EQ(bound[2], 12);
}

TEST(ErrorBound, ContainsTheFurnaceErrorPerChannelAndIsNotVacuous) {
  // The closed cube, E = 1 everywhere, rho = (0.2, 0.5, 0.8): B = E / (1 - rho) = (1.25, 2, 5)
  // exactly, for the discrete system too (the form factors of a closed convex room sum to 1).
  // Stopped early and late, the error of every channel lies within the bound, and the bound is
  // within a factor of the error (a bound of rho_max / (1 - rho_max) times something larger
  // than the unshot radiosity, or one missing the 1 / (1 - rho) of the light to come, fails).
  Scene cube = load_scene(kScenes / "closed-cube/scene.json");
  cube.materials[0].reflectance = Rgb(0.2, 0.5, 0.8);
  const Rgb exact(1.25, 2, 5);
  double previous = INFINITY;
  for (const double unshot : {0.5, 0.1, 1e-2, 1e-3}) {
    SolverSettings settings;
    settings.patch_size = 0.25;
    settings.unshot_fraction = unshot;
    settings.refine_threshold = 0;
    const Solution s = solve_scene(cube, settings);
    const Rgb error = largest_error(s, exact);
    const Rgb bound = s.stats.error_bound;
    for (int c = 0; c < 3; ++c) {
      // The discrete system's B* is E / (1 - rho) to the rounding of its form factors' sum
      // (measured: 3e-10 relative, with red's bound at 2e-16 at the last threshold).
      EXPECT_LE(error[c], bound[c] + 1e-8 * exact[c]) << "unshot " << unshot << ", channel " << c;
      // Stopped early, the bound is not vacuous: measured, the error is about half of it.
      if (unshot >= 0.1) {
        EXPECT_GT(error[c], 0.05 * bound[c]) << "unshot " << unshot;
      }
    }
    EXPECT_LT(bound.maxCoeff(), previous) << "the bound falls with the unshot light";
    previous = bound.maxCoeff();
    std::cout << "furnace, unshot " << unshot << ": error (" << error.transpose() << "), bound ("
              << bound.transpose() << ")\n";
  }
}

TEST(ErrorBound, ContainsTheDistanceToTheSameSystemSolvedFurther) {
  // One face of the closed cube emits, the rest only reflect: no closed form, but a solve of
  // the same discrete system (no adaptive refinement: the same elements; the same seed: the
  // same form factors) run to 1e-9 of the light is B* within its own, tiny, bound. The early
  // solve's distance to it must lie within the early bound plus that one. For both solvers:
  // the hierarchical one's bound is on its links' system, swept (radiosity/hierarchical_solver.h).
  Scene cube = load_scene(kScenes / "closed-cube/scene.json");
  Material lamp = cube.materials[0];
  lamp.name = "lamp";
  lamp.emission = Rgb(3, 2, 1);
  cube.materials[0].emission = Rgb::Zero();
  cube.materials[0].reflectance = Rgb(0.7, 0.5, 0.3);
  cube.materials.push_back(lamp);
  cube.polygons[1].material = 1;  // the top face
  for (const auto method :
       {SolverSettings::Method::progressive, SolverSettings::Method::hierarchical}) {
    const char* name =
        method == SolverSettings::Method::progressive ? "progressive" : "hierarchical";
    SolverSettings settings;
    settings.method = method;
    settings.patch_size = 0.25;
    settings.refine_threshold = 0;  // the same elements at every stop
    settings.faint_share = 0;       // the same links at every stop
    settings.unshot_fraction = 1e-9;
    const Solution converged = solve_scene(cube, settings);
    for (const double unshot : {0.3, 0.03, 3e-3}) {
      settings.unshot_fraction = unshot;
      const Solution s = solve_scene(cube, settings);
      ASSERT_EQ(s.leaves(), converged.leaves());
      Rgb distance = Rgb::Zero();
      for (const int e : s.leaves()) {
        distance = distance.cwiseMax(
            (s.elements[e].radiosity - converged.elements[e].radiosity).cwiseAbs());
      }
      for (int c = 0; c < 3; ++c) {
        EXPECT_LE(distance[c], s.stats.error_bound[c] + converged.stats.error_bound[c])
            << name << ", unshot " << unshot << ", channel " << c;
        EXPECT_GT(distance[c], 0.01 * s.stats.error_bound[c]) << name << ", unshot " << unshot;
      }
    }
  }
}

}  // namespace
}  // namespace rad
