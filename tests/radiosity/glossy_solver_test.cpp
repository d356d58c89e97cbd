// The solver and glossy surfaces (issue 20): what they reflect into their lobes is not carried
// by the coarse solution but counted in the ledger as "redirected" (paper 003's transfer is the
// local pass's), and a glossy surface is no mirror to the solver.
#include <gtest/gtest.h>

#include "radiosity/solver.h"
#include "scene/ray_caster.h"
#include "tests/scene_builder.h"

namespace rad {
namespace {

using test::SceneBuilder;

TEST(GlossySolver, RedirectsWhatItsLobeReflectsAndSaysSo) {
  // A light over a glossy floor (diffuse 0.2, specular 0.6, gloss 0.1): each floor element
  // takes in H, reflects 0.2 H diffusely (its radiosity) and redirects 0.6 H; the ledger
  // balances with that term, which is 0.6 of what the floor receives.
  SceneBuilder b;
  const int brushed =
      b.material("brushed", Rgb::Constant(0.2), Rgb::Zero(), Rgb::Zero(), Rgb::Constant(0.6));
  b.scene().materials[brushed].gloss = 0.1;
  b.rectangle(-1, 1, -1, 1, 0, false, brushed);
  b.scene().lights.push_back({Vec3(0.2, 0.1, 0.8), Rgb(1, 2, 3)});
  const Solution s = solve(RayCaster(b.scene()), SolverSettings{});
  const SolveStats& st = s.stats;
  Rgb received = Rgb::Zero();
  for (const int e : s.leaves()) {
    const Element& el = s.elements[e];
    received += el.irradiance * el.area;
    EXPECT_LE((el.radiosity - 0.2 * el.irradiance).cwiseAbs().maxCoeff(),
              1e-12 * el.irradiance.maxCoeff());
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(st.absorbed[c] + st.escaped[c] + st.unshot[c] + st.redirected[c], st.emitted[c],
                1e-9 * st.emitted[c]);
    EXPECT_NEAR(st.redirected[c], 0.6 * received[c], 1e-9 * received[c]);
  }
  EXPECT_GT(st.redirected.minCoeff(), 0);
}

}  // namespace
}  // namespace rad
