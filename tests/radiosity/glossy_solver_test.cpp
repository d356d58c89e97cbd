// The solver and glossy surfaces (issue 20): what glossy mirrors reflect into their lobes is
// not carried by the coarse solution but counted in the ledger as "redirected" (paper 003's
// transfer is the local pass's), and a glossy surface is no mirror to the solver; a roughened
// pane is carried as the filter of its glossy transmittance.
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

TEST(GlossySolver, CarriesARoughenedPaneAsTheFilterOfItsTransmittance) {
  // At the scale of patches a pane's blur matters little: the solver carries a roughened pane
  // (glossy transmittance 0.6, a light at its back) exactly as a plain filter of transmittance
  // 0.6, element for element, and redirects nothing.
  const auto scene = [](bool rough) {
    SceneBuilder b;
    b.rectangle(-2, 2, -2, 2, 0, false, b.material("floor", Rgb::Constant(0.5), Rgb::Zero()));
    const int pane = b.material("pane", Rgb::Zero(), Rgb::Zero());
    Material& m = b.scene().materials[pane];
    if (rough) {
      m.gloss = 0.1;
      m.glossy_transmittance = Rgb(0.6, 0.5, 0.4);
    } else {
      m.transmittance = Rgb(0.6, 0.5, 0.4);
    }
    b.rectangle(-0.5, 0.5, -0.5, 0.5, 1, true, pane);
    b.scene().lights.push_back({Vec3(0.1, 0.2, 1.6), Rgb(1, 2, 3)});
    return b.scene();
  };
  SolverSettings settings;
  settings.refine_threshold = 0;  // the same mesh in both
  const Scene rough = scene(true), plain = scene(false);
  const Solution a = solve(RayCaster(rough), settings), b = solve(RayCaster(plain), settings);
  ASSERT_EQ(a.elements.size(), b.elements.size());
  for (size_t e = 0; e < a.elements.size(); ++e)
    ASSERT_EQ(a.elements[e].radiosity, b.elements[e].radiosity) << "element " << e;
  EXPECT_EQ(a.stats.redirected, Rgb::Zero());
  EXPECT_EQ(a.stats.absorbed, b.stats.absorbed);
}

}  // namespace
}  // namespace rad
