// Glossy transfer in the local pass (issue 20, paper 003): the beams of a scene's point lights
// and emitters through its glossy polygons, found by the cone hierarchy, against the beams
// summed by hand, the cubature of the physics (tests/glossy_cubature.h), and the first-order
// visibility of the scatterer.
#include "specular/glossy_transfer.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "localpass/local_pass.h"
#include "reference/path_tracer.h"
#include "scene/polygon_faces.h"
#include "tests/glossy_cubature.h"
#include "tests/path_trace_checks.h"
#include "tests/scene_builder.h"

namespace rad {
namespace {

using test::SceneBuilder;

const Vec3 kLight(-0.5, 0.2, 0.4);
const Rgb kIntensity(1, 2, 3);
const Rgb kSpecular(0.8, 0.6, 0.4);
const Vec3 kUp(0, 0, 1);

/// A black floor, a glossy square [-0.2, 0.4] x [-0.3, 0.3] at z = 1 facing down, a light under
/// it; optionally a black card between the light and the square.
Scene glossy_scene(double sigma, bool card = false) {
  SceneBuilder b;
  const int black = b.material("black", Rgb::Zero(), Rgb::Zero());
  b.rectangle(-3, 3, -3, 3, 0, false, black);
  const int brushed =
      b.material("brushed", Rgb::Constant(0.1), Rgb::Zero(), Rgb::Zero(), kSpecular);
  b.scene().materials[brushed].gloss = sigma;
  b.rectangle(-0.2, 0.4, -0.3, 0.3, 1, true, brushed);
  if (card)
    b.polygon({{-0.3, 0.1, 0.6}, {-0.3, 0.3, 0.6}, {-0.3, 0.3, 0.8}, {-0.3, 0.1, 0.8}}, black);
  b.scene().lights.push_back({kLight, kIntensity});
  return b.scene();
}

const Vec3 kFloor[] = {Vec3(0.9, -0.1, 0), Vec3(0.6, 0.2, 0), Vec3(1.2, 0.3, 0), Vec3(1.6, -0.5, 0),
                       Vec3(0.3, 0.0, 0)};

/// The physics of a glossy polygon (each of its triangles integrated by the cubature) at x on
/// the floor, per unit intensity and weight: reflected, or passed through (a pane).
double physics_of(const Polygon& polygon, const Vec3& light, double sigma, const Vec3& x,
                  bool transmits) {
  double physics = 0;
  for (const auto& [a, b, c] : triangulate(project_to_plane(polygon.vertices, polygon.normal))) {
    const GlossyTriangle t{{polygon.vertices[a], polygon.vertices[b], polygon.vertices[c]},
                           {polygon.normal, polygon.normal, polygon.normal},
                           transmits};
    physics += test::GlossyCubature(GlossyBeam(light, Rgb::Ones(), t, Rgb::Ones(), sigma), x, kUp)
                   .integrate(1e-10);
  }
  return physics;
}

/// The local pass (vertex tracing) of `scene` with its glossy triangles split 32 x 32: pieces
/// small against the lobes, where the beams come within the model's 13% of the physics.
LocalPass finely_split_pass(const Scene& scene) {
  LocalPassSettings settings;
  settings.glossy.split = 32;
  return LocalPass(scene, faces_from_polygons(scene), Method::vertex, settings);
}

TEST(GlossyTransfer, TheHierarchyWithoutACutIsEveryBeam) {
  // The cones widened without end cull nothing the beams would send: the same sum as every
  // beam at every receiver, to rounding; with the default cut at 5 sigma, what is dropped is
  // below 1e-3 of the glossy light.
  for (const double sigma : {0.05, 0.2}) {
    const Scene scene = glossy_scene(sigma);
    GlossySettings every, uncut, cut;
    every.hierarchy = false;
    uncut.cutoff = std::numeric_limits<double>::infinity();
    const GlossyTransfer plain(scene, every), whole(scene, uncut), culled(scene, cut);
    ASSERT_EQ(plain.beam_count(), 2 * 64) << "one light, two triangles of 8 x 8 pieces";
    int fewer = 0;
    for (const Vec3& x : kFloor) {
      const Rgb reference = plain.irradiance(x, kUp).irradiance;
      ASSERT_GT(reference.maxCoeff(), 0);
      EXPECT_LE((whole.irradiance(x, kUp).irradiance - reference).cwiseAbs().maxCoeff(),
                1e-12 * reference.maxCoeff());
      const GlossyTransfer::Result r = culled.irradiance(x, kUp);
      EXPECT_LE((r.irradiance - reference).cwiseAbs().maxCoeff(), 1e-3 * reference.maxCoeff())
          << "sigma " << sigma << " at " << x.transpose();
      fewer += r.beams < plain.beam_count();
    }
    if (sigma == 0.05) {
      EXPECT_GT(fewer, 0) << "the cut must skip beams somewhere";
    }
  }
}

TEST(GlossyTransfer, TheCutDropsOnlyBeamsWhoseLobesMissTheReceiverByTheCutoff) {
  // The hierarchy's proof: a beam is skipped at x only if every scatter angle between x - P and
  // the lobe's centre d(P), P over its piece, exceeds cutoff sigma. Sampled densely over each
  // piece: the beams with some angle below cutoff sigma must all be evaluated, so the cut sum
  // is at least theirs. At cutoff 1 the cut is aggressive enough to show it.
  const double sigma = 0.05;
  const Scene scene = glossy_scene(sigma);
  GlossySettings settings;
  settings.cutoff = 1;
  const GlossyTransfer culled(scene, settings);
  int skipped = 0;
  for (const Vec3& x : {Vec3(0.9, -0.1, 0), Vec3(0.7, 0.3, 0), Vec3(1.1, -0.3, 0)}) {
    Rgb must = Rgb::Zero(), all = Rgb::Zero();
    for (const GlossyBeam& beam : culled.beams()) {
      const auto& v = beam.triangle().vertex;
      double nearest = INFINITY;
      const int grid = 12;
      for (int i = 0; i <= grid; ++i) {
        for (int j = 0; i + j <= grid; ++j) {
          const std::array<double, 3> w{1.0 - (i + j) / double(grid), i / double(grid),
                                        j / double(grid)};
          const Vec3 p = w[0] * v[0] + w[1] * v[1] + w[2] * v[2];
          const Vec3 d = beam.scattered(p, w), to = x - p;
          nearest = std::min(nearest, std::atan2(to.cross(d).norm(), to.dot(d)));
        }
      }
      const Rgb e = beam.irradiance(x, kUp);
      all += e;
      if (nearest < settings.cutoff * sigma) must += e;
    }
    const GlossyTransfer::Result r = culled.irradiance(x, kUp);
    skipped += r.beams < culled.beam_count();
    EXPECT_GE(r.irradiance[0], must[0] * (1 - 1e-12)) << "at " << x.transpose();
    EXPECT_LE(r.irradiance[0], all[0] * (1 + 1e-12));
  }
  EXPECT_GT(skipped, 0);
}

TEST(GlossyTransfer, TheLocalPassKeepsItApartAndNearThePhysics) {
  // Split 32 x 32, the local pass's glossy part comes within the model's 13% of the physics
  // (each triangle of the square integrated by the cubature, times the specular weight); the
  // certified part is the light's direct light alone: the glossy square is no mirror to it.
  const double sigma = 0.1;
  const Scene scene = glossy_scene(sigma);
  const LocalPass pass = finely_split_pass(scene);
  for (const Vec3& x : kFloor) {
    const LocalPassResult r = pass.gather(x, kUp, 0);
    const double physics = physics_of(scene.polygons[1], kLight, sigma, x, false);
    const Rgb expected = kIntensity.cwiseProduct(kSpecular) * physics;
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(r.glossy[ch] / expected[ch], 1, 0.13) << "at " << x.transpose();
    const Vec3 to = kLight - x;
    const Rgb direct = kIntensity * (to.z() / std::pow(to.norm(), 3));
    EXPECT_LE((r.irradiance - direct).cwiseAbs().maxCoeff(), 1e-12 * direct.maxCoeff())
        << "the certified part: the direct light, no mirror image of the light";
    EXPECT_EQ(r.bound, Rgb::Zero());
    EXPECT_GT(r.glossy_beams, 0);
  }
}

TEST(GlossyTransfer, ThePathTracerSamplesTheLobeAndMeetsThePhysics) {
  // The path tracer's glossy surfaces (next-event estimation of the lights through the lobe,
  // and one direction drawn from it) against the cubature of the same physics: the floor's
  // irradiance less the light's own direct light is the glossy part, within 4 standard errors.
  // The square's diffuse part is 0 here, so that nothing else reaches the floor.
  for (const double sigma : {0.05, 0.2}) {
    Scene scene = glossy_scene(sigma);
    scene.materials[1].reflectance = Rgb::Zero();
    const PathTracer tracer(scene);
    uint64_t seed = 0;
    for (const Vec3& x : {Vec3(0.9, -0.1, 0), Vec3(1.2, 0.3, 0), Vec3(0.6, 0.2, 0)}) {
      const double physics = physics_of(scene.polygons[1], kLight, sigma, x, false);
      const Vec3 to = kLight - x;
      const Rgb direct = kIntensity * (to.z() / std::pow(to.norm(), 3));
      PathTraceEstimate e = tracer.irradiance(x, kUp, 2000000, ++seed);
      e.mean -= direct;
      EXPECT_TRUE(test::within(e, kIntensity.cwiseProduct(kSpecular) * physics, 0.05, 1e-6))
          << "sigma " << sigma << " at " << x.transpose();
    }
  }
}

/// A roughened pane [-0.4, 0.4]^2 at z = 1 facing down (its back to the light above it) over a
/// black floor: glossy transmittance kPane, no diffuse part.
const Rgb kPane(0.7, 0.5, 0.3);
const Vec3 kAbove(0.2, 0.1, 1.7);
Scene pane_scene(double sigma) {
  SceneBuilder b;
  const int black = b.material("black", Rgb::Zero(), Rgb::Zero());
  b.rectangle(-3, 3, -3, 3, 0, false, black);
  const int frosted = b.material("frosted", Rgb::Zero(), Rgb::Zero());
  b.scene().materials[frosted].gloss = sigma;
  b.scene().materials[frosted].glossy_transmittance = kPane;
  b.rectangle(-0.4, 0.4, -0.4, 0.4, 1, true, frosted);
  b.scene().lights.push_back({kAbove, kIntensity});
  return b.scene();
}

TEST(GlossyTransfer, ARoughenedPanePassesTheLightThroughItsLobeOnly) {
  // 003 Fig. 13: the pane is opaque to straight lines (no direct light under it, the certified
  // part 0 there), and what it passes comes by the beams, within the model's 13% of the physics
  // split fine; the path tracer, which samples the pane's lobe from either side, meets the
  // physics within 4 standard errors.
  const double sigma = 0.15;
  const Scene scene = pane_scene(sigma);
  const LocalPass pass = finely_split_pass(scene);
  const PathTracer tracer(scene);
  uint64_t seed = 0;
  for (const Vec3& x : {Vec3(0.25, 0.1, 0), Vec3(0.0, -0.2, 0), Vec3(-0.3, 0.3, 0)}) {
    const LocalPassResult r = pass.gather(x, kUp, 0);
    EXPECT_EQ(r.irradiance, Rgb::Zero()) << "the pane hides the light from straight lines";
    const Rgb expected =
        kIntensity.cwiseProduct(kPane) * physics_of(scene.polygons[1], kAbove, sigma, x, true);
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(r.glossy[ch] / expected[ch], 1, 0.13) << "at " << x.transpose();
    EXPECT_TRUE(test::within(tracer.irradiance(x, kUp, 400000, ++seed), expected, 0.05, 1e-6))
        << "at " << x.transpose();
  }
}

TEST(GlossyTransfer, ACardBetweenThePaneAndTheFloorShadowsItsLight) {
  // Second-order shadows (beyond 003): a black card at z = 0.2 over a floor point hides every
  // piece of the pane from it, so its glossy light is 0; 003's model as printed (shadows off)
  // lights it as if the card were not there. A point beside the card keeps its light.
  const double sigma = 0.15;
  Scene open = pane_scene(sigma), carded = pane_scene(sigma);
  SceneBuilder b;
  b.scene() = carded;
  b.rectangle(-0.6, 0.6, -0.6, 0.6, 0.2, false, 0);
  carded = b.scene();
  GlossySettings printed;
  printed.shadows = false;
  const GlossyTransfer with_card(carded, {}), as_printed(carded, printed), without(open, {});
  const Vec3 under(0.1, 0.0, 0), beside(1.5, 0.2, 0);
  ASSERT_GT(without.irradiance(under, kUp).irradiance.maxCoeff(), 0);
  EXPECT_EQ(with_card.irradiance(under, kUp).irradiance, Rgb::Zero());
  EXPECT_EQ(as_printed.irradiance(under, kUp).irradiance,
            without.irradiance(under, kUp).irradiance);
  const Rgb free = without.irradiance(beside, kUp).irradiance;
  ASSERT_GT(free.maxCoeff(), 0);
  EXPECT_LE((with_card.irradiance(beside, kUp).irradiance - free).cwiseAbs().maxCoeff(),
            1e-12 * free.maxCoeff());
}

TEST(GlossyTransfer, ACardBetweenTheLightAndTheScattererShadowsPartOfIt) {
  // First-order visibility: beams whose piece the light cannot see are not made.
  const GlossyTransfer open(glossy_scene(0.1), {}), shaded(glossy_scene(0.1, true), {});
  EXPECT_LT(shaded.beam_count(), open.beam_count());
  EXPECT_GT(shaded.beam_count(), 0);
}

TEST(GlossyTransfer, AnEmitterSplitIntoPointsLightsItLikeTheLightItStandsFor) {
  // A small lamp of area A and exitance M facing the square: from afar its pieces are a point of
  // intensity (M A / pi) cos toward the square; against a point light of that intensity at its
  // centre (the square's centre direction), the glossy light agrees within the cosine's
  // variation over the square (a few %).
  const double sigma = 0.1, side = 0.02;
  Scene lamp = glossy_scene(sigma);
  lamp.lights.clear();
  SceneBuilder b;
  b.scene() = lamp;
  const int emitter = b.material("lamp", Rgb::Zero(), Rgb::Constant(1000));
  // Facing the square's centre (0.1, 0, 1) from kLight.
  const Vec3 w = (Vec3(0.1, 0, 1) - kLight).normalized();
  const Vec3 u = w.cross(Vec3::UnitY()).normalized(), v = w.cross(u);
  b.polygon({kLight + side * (-u - v), kLight + side * (u - v), kLight + side * (u + v),
             kLight + side * (-u + v)},
            emitter);
  const Scene& with_lamp = b.scene();
  ASSERT_GT(with_lamp.polygons.back().normal.dot(w), 0.999);
  Scene with_light = glossy_scene(sigma);
  const double area = 4 * side * side;
  with_light.lights = {{kLight, Rgb::Constant(1000 * area / std::numbers::pi)}};
  const GlossyTransfer from_lamp(with_lamp, {}), from_light(with_light, {});
  for (const Vec3& x : kFloor) {
    const double a = from_lamp.irradiance(x, kUp).irradiance[0];
    const double l = from_light.irradiance(x, kUp).irradiance[0];
    EXPECT_NEAR(a / l, 1, 0.05) << "at " << x.transpose();
  }
}

}  // namespace
}  // namespace rad
