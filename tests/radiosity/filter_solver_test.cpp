// The progressive solver with filters (paper 000 §2.2), and glass carried as filters: shadow
// rays carry the transmittance per channel, and the ledger counts what a filter absorbs at its
// front and at its back.
#include <gtest/gtest.h>

#include "radiosity/solver.h"
#include "scene/ray_caster.h"
#include "tests/scene_builder.h"

namespace rad {
namespace {

using test::SceneBuilder;

Solution solve_scene(const Scene& scene, SolverSettings settings) {
  return solve(RayCaster(scene), settings);
}

/// A grey floor under a lamp, and (optionally) a black filter half way between them, as wide
/// as the floor: every floor point sees the whole lamp through it (the segment from a floor
/// point to a lamp point crosses z = 1 at their midpoint), and the bounding box, which sets the
/// patch size, is the same with and without it.
Scene lamp_over_floor(const Rgb* transmittance) {
  SceneBuilder b;
  b.rectangle(-2, 2, -2, 2, 0, false, b.material("floor", Rgb::Constant(0.5), Rgb::Zero()));
  b.rectangle(-0.5, 0.5, -0.5, 0.5, 2, true, b.material("lamp", Rgb::Zero(), Rgb(1, 2, 3)));
  if (transmittance) {
    b.rectangle(-2, 2, -2, 2, 1, true,
                b.material("glass", Rgb::Zero(), Rgb::Zero(), *transmittance));
  }
  return b.scene();
}

TEST(FilterSolver, AFilterOverTheLampScalesTheFloorByItsTransmittance) {
  // Every floor point sees the lamp through the filter and nothing else radiates back (black
  // lamp, black filter: what the floor reflects leaves or is absorbed), so each floor element
  // holds T times what it holds without the filter, per channel.
  const Rgb t(0.2, 0.5, 0.8);
  const Scene open = lamp_over_floor(nullptr), filtered = lamp_over_floor(&t);
  SolverSettings settings;
  settings.refine_threshold = 0;  // the same mesh in both
  const Solution a = solve_scene(open, settings), b = solve_scene(filtered, settings);
  int floor_elements = 0;
  for (size_t e = 0; e < a.elements.size(); ++e) {
    if (a.elements[e].polygon != 0) continue;
    ASSERT_LT(e, b.elements.size());
    ++floor_elements;
    const Rgb expected = t.cwiseProduct(a.elements[e].radiosity);
    EXPECT_LE((b.elements[e].radiosity - expected).cwiseAbs().maxCoeff(),
              1e-12 * expected.maxCoeff())
        << "element " << e << ": " << b.elements[e].radiosity.transpose() << " against "
        << expected.transpose();
  }
  EXPECT_GT(floor_elements, 10);
}

TEST(FilterSolver, LedgerCountsWhatFiltersAbsorbAtFrontAndBack) {
  // emitted = absorbed + escaped + unshot, and the filter's share is in "absorbed": with an
  // opaque black floor and a black filter (T = 0.5) over the lamp, the lamp's light through
  // the filter's back is half absorbed there, half passed on to the floor (absorbed there or
  // escaping round it).
  const Rgb t = Rgb::Constant(0.5);
  SceneBuilder b;
  b.scene() = lamp_over_floor(&t);
  // A grey blocker under the filter and a second filter over part of the lamp: shadows, seen
  // through filters, that refinement resolves.
  b.rectangle(-0.3, 0.3, -0.3, 0.3, 0.5, true, b.material("grey", Rgb::Constant(0.5), Rgb::Zero()));
  b.rectangle(-0.3, 0.8, -1, 1, 1.5, false,
              b.material("gel", Rgb::Constant(0.2), Rgb::Zero(), Rgb(0.3, 0.6, 0.1)));
  const Scene& scene = b.scene();
  SolverSettings settings;
  const Solution s = solve_scene(scene, settings);
  const SolveStats& st = s.stats;
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(st.absorbed[c] + st.escaped[c] + st.unshot[c] + st.redirected[c], st.emitted[c],
                1e-9 * st.emitted[c])
        << "channel " << c;
  }
  // The lamp faces down into the filters, which cover most of its lower hemisphere: most of
  // its light reaches a filter's back, and half of that or more is absorbed there (measured:
  // 0.61 of it absorbed in all, 0.39 when the backs are not asked).
  EXPECT_GT(st.absorbed.x(), 0.5 * st.emitted.x());
  EXPECT_GT(st.escaped.x(), 0);
  EXPECT_GT(st.refined, 0) << "the ledger must hold through refinement too";
}

/// lamp_over_floor with, in the filter's place, a slab of glass [-2, 2]^2 x [0.9, 1.1] (a
/// refracting box, 000 §4) and refraction followed `refraction_depth` deep.
Scene lamp_over_glass(const Refraction& glass, int refraction_depth) {
  SceneBuilder b;
  b.scene() = lamp_over_floor(nullptr);
  b.box(Vec3(-2, -2, 0.9), Vec3(2, 2, 1.1), b.material("glass", glass));
  b.scene().refraction_depth = refraction_depth;
  return b.scene();
}

TEST(GlassSolver, CarriesAPaneAsAFilterOfWhatItsTwoCrossingsPass) {
  // Every floor point sees the lamp through the slab's two faces, so with glass carried as
  // filters (SolverSettings::glass_as_filters) each floor element holds T^2 times what it holds
  // without the slab: T the interface's transmittance, or with Fresnel at normal incidence
  // 1 - ((1.5 - 1) / (1.5 + 1))^2 = 0.96. Opaque glass (the setting off, or refraction off in
  // the scene) leaves the floor dark.
  Refraction tinted;
  tinted.transmittance = Rgb(0.9, 0.7, 0.5);
  Refraction fresnel;
  fresnel.fresnel = true;
  const struct {
    Refraction glass;
    Rgb passed;
  } cases[] = {{tinted, Rgb(0.81, 0.49, 0.25)}, {fresnel, Rgb::Constant(0.96 * 0.96)}};
  SolverSettings settings;
  settings.refine_threshold = 0;  // the same mesh in all
  const Solution open = solve(RayCaster(lamp_over_floor(nullptr)), settings);
  for (const auto& c : cases) {
    const Solution glass = solve(RayCaster(lamp_over_glass(c.glass, 2)), settings);
    SolverSettings opaque_settings = settings;
    opaque_settings.glass_as_filters = false;
    const Solution opaque = solve(RayCaster(lamp_over_glass(c.glass, 2)), opaque_settings);
    const Solution off = solve(RayCaster(lamp_over_glass(c.glass, 0)), settings);
    int floor_elements = 0;
    for (size_t e = 0; e < open.elements.size(); ++e) {
      if (open.elements[e].polygon != 0) continue;
      ++floor_elements;
      const Rgb expected = c.passed.cwiseProduct(open.elements[e].radiosity);
      ASSERT_LE((glass.elements[e].radiosity - expected).cwiseAbs().maxCoeff(),
                1e-12 * expected.maxCoeff())
          << "element " << e << ": " << glass.elements[e].radiosity.transpose() << " against "
          << expected.transpose();
      ASSERT_EQ(opaque.elements[e].radiosity, Rgb::Zero()) << "element " << e;
      ASSERT_EQ(off.elements[e].radiosity, Rgb::Zero()) << "element " << e;
    }
    EXPECT_GT(floor_elements, 10);
    for (int ch = 0; ch < 3; ++ch) {
      const SolveStats& st = glass.stats;
      EXPECT_NEAR(st.absorbed[ch] + st.escaped[ch] + st.unshot[ch], st.emitted[ch],
                  1e-9 * st.emitted[ch]);
    }
  }
}

}  // namespace
}  // namespace rad
