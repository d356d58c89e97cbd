// The progressive solver with point lights (issue 20): they shoot once, first; each element
// takes in I cos / r^2 at its centroid (children re-gather it), the ledger counts their power,
// and in a closed box the reflected power is what the furnace identity says.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "localpass/local_pass.h"
#include "radiosity/solution_faces.h"
#include "radiosity/solver.h"
#include "reference/path_tracer.h"
#include "scene/ray_caster.h"
#include "tests/mirrored_light.h"
#include "tests/scene_builder.h"

namespace rad {
namespace {

using test::SceneBuilder;

void expect_balanced(const SolveStats& st) {
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(st.absorbed[c] + st.escaped[c] + st.unshot[c] + st.redirected[c], st.emitted[c],
                1e-9 * st.emitted[c])
        << "channel " << c << ": emitted " << st.emitted[c] << " absorbed " << st.absorbed[c]
        << " escaped " << st.escaped[c] << " unshot " << st.unshot[c];
  }
}

TEST(PointLightSolver, EveryFloorElementHoldsTheInverseSquareLawAtItsCentroid) {
  // A grey floor under a light and nothing else: no element receives anything but the light,
  // so each leaf's irradiance is I cos / r^2 at its centroid, children of refinement included
  // (they re-gather the light), and its radiosity rho times that.
  SceneBuilder b;
  const Rgb rho(0.5, 0.4, 0.3);
  b.rectangle(-2, 2, -2, 2, 0, false, b.material("floor", rho, Rgb::Zero()));
  const PointLight light{Vec3(0.4, -0.3, 0.7), Rgb(1, 2, 3)};
  b.scene().lights.push_back(light);
  const Scene& scene = b.scene();
  const Solution s = solve(RayCaster(scene), SolverSettings{});
  EXPECT_GT(s.stats.refined, 0) << "the test must reach the children's re-gather";
  for (const int e : s.leaves()) {
    const Element& el = s.elements[e];
    const Rgb expected = light.unoccluded_irradiance(el.centroid, Vec3(0, 0, 1));
    ASSERT_LE((el.irradiance - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.maxCoeff())
        << "element " << e << " at " << el.centroid.transpose();
    ASSERT_LE((el.radiosity - rho.cwiseProduct(expected)).cwiseAbs().maxCoeff(),
              1e-12 * expected.maxCoeff());
  }
  expect_balanced(s.stats);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(s.stats.emitted[c], 4 * std::numbers::pi * light.intensity[c], 1e-12);
  EXPECT_GT(s.stats.escaped.minCoeff(), 0) << "the upper half of its light leaves";
}

TEST(PointLightSolver, AMirrorsImageOfTheLightReachesTheFloor) {
  // A black floor beside a perfect mirror (tests/mirrored_light.h): the lights' one shot is all
  // any element receives, so each floor leaf holds the closed form at its centroid, the light's
  // image included (without it, the leaves in the image's light would hold the straight light
  // alone). With a grey floor the ledger still balances: the mirror's specular part is counted
  // where it lands, not also as escaped.
  const test::MirroredLight black;
  const Solution s = solve(RayCaster(black.scene), SolverSettings{});
  int reflected = 0;
  for (const int e : s.leaves()) {
    const Element& el = s.elements[e];
    if (el.polygon != 0) continue;
    const Rgb expected = black.expected(el.centroid.x(), el.centroid.y());
    ASSERT_LE((el.irradiance - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.maxCoeff())
        << "element " << e << " at " << el.centroid.transpose();
    reflected += black.reflected(el.centroid.x(), el.centroid.y()) != Rgb::Zero();
  }
  EXPECT_GT(reflected, 3) << "leaves in the image's light";
  const Solution grey =
      solve(RayCaster(test::MirroredLight(Rgb::Constant(0.5)).scene), SolverSettings{});
  expect_balanced(grey.stats);
  EXPECT_GT(grey.stats.escaped.minCoeff(), 0) << "an open scene";
}

/// A closed unit cube of reflectance rho facing in, a light inside.
Scene lit_room(double rho) {
  SceneBuilder b;
  b.box(Vec3::Zero(), Vec3::Ones(), b.material("white", Rgb::Constant(rho), Rgb::Zero()));
  for (Polygon& p : b.scene().polygons) {
    std::reverse(p.vertices.begin(), p.vertices.end());
    p.normal = -p.normal;
  }
  b.scene().lights.push_back({Vec3(0.35, 0.6, 0.45), Rgb(1, 0.5, 0.25)});
  return b.scene();
}

TEST(PointLightSolver, AClosedRoomReflectsRhoOverOneMinusRhoOfThePower) {
  // Everything sent is absorbed after 1 / (1 - rho) bounces on average: the walls receive
  // P / (1 - rho) in all and reflect rho P / (1 - rho), less what is still unshot.
  const double rho = 0.5;
  const Scene scene = lit_room(rho);
  const Solution s = solve(RayCaster(scene), SolverSettings{});
  expect_balanced(s.stats);
  const Rgb power = scene.light_power();
  EXPECT_LT(std::abs(s.stats.escaped.sum()), 1e-2 * power.sum()) << "closed: nothing escapes";
  Rgb reflected = Rgb::Zero();
  for (const int e : s.leaves()) reflected += s.elements[e].radiosity * s.elements[e].area;
  for (int c = 0; c < 3; ++c) {
    const double expected = rho * power[c] / (1 - rho);
    const double unshot = rho / (1 - rho) * s.stats.unshot[c];  // what it would still add
    EXPECT_NEAR(reflected[c] + unshot, expected, 1e-2 * expected) << "channel " << c;
  }
}

TEST(PointLightSolver, TheLocalPassOverTheSolutionMatchesThePathTracerInTheRoom) {
  // End to end: the exact direct light plus the solution's reflected light, gathered exactly,
  // against the path tracer, which shares nothing with the solver but the light's closed form.
  const Scene scene = lit_room(0.5);
  const Solution s = solve(RayCaster(scene), SolverSettings{});
  const LocalPass pass(scene, faces_from_solution(scene, s), Method::vertex);
  const PathTracer tracer(scene);
  const std::pair<Vec3, Vec3> points[] = {{Vec3(0.5, 0.5, 0), Vec3(0, 0, 1)},
                                          {Vec3(0.1, 0.9, 0), Vec3(0, 0, 1)},
                                          {Vec3(1, 0.3, 0.8), Vec3(-1, 0, 0)},
                                          {Vec3(0.7, 0.2, 1), Vec3(0, 0, -1)}};
  uint64_t seed = 0;
  for (const auto& [x, n] : points) {
    const Rgb local = pass.gather(x, n, 0).irradiance;
    const PathTraceEstimate e = tracer.irradiance(x, n, 20000, ++seed);
    for (int c = 0; c < 3; ++c) {
      // The coarse solution's own error (elements constant, centroid-sampled): 2% of H.
      EXPECT_NEAR(local[c], e.mean[c], 4 * e.standard_error[c] + 0.02 * e.mean[c])
          << "at " << x.transpose() << " channel " << c;
    }
  }
}

}  // namespace
}  // namespace rad
