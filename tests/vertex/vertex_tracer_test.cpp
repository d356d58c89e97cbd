// Vertex tracing against the closed forms, the other exact method and its own fast paths.
#include "vertex/vertex_tracer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <random>

#include "hemisphere/hemisphere_gatherer.h"
#include "radiosity/solver.h"
#include "scene/polygon_faces.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "tests/closed_forms.h"
#include "tests/coarse_solution.h"
#include "tests/random_scenes.h"
#include "tests/scene_builder.h"
#include "tests/surface_points.h"
#include "vertex/interpenetration.h"

namespace rad {
namespace {

using test::SceneBuilder;

double traced(const Scene& scene, const Vec3& x, const Vec3& n) {
  return VertexTracer(scene).gather(x, n).irradiance.x();
}

TEST(VertexTracing, MatchesHowellB3) {
  for (const auto& c : test::kHowellB3) {
    SceneBuilder b;
    b.rectangle(0, c.a, 0, c.b, c.c, true, b.material("lamp", Rgb::Zero(), Rgb::Ones()));
    EXPECT_NEAR(traced(b.scene(), Vec3::Zero(), Vec3::UnitZ()), c.F, 1e-12 * c.F)
        << c.a << " " << c.b << " " << c.c;
  }
}

TEST(VertexTracing, BlockerOverLight) {
  SceneBuilder b;
  const int lamp = b.material("lamp", Rgb::Zero(), Rgb::Ones());
  const int grey = b.material("grey", Rgb::Constant(0.5), Rgb::Zero());
  b.rectangle(-1, 1, -1, 1, 2, true, lamp);
  b.rectangle(-0.3, 0.5, -0.2, 0.9, 1, true, grey);
  const Vec3 x(0.1, 0.05, 0);
  const double h = HemisphereGatherer(faces_from_polygons(b.scene()), b.scene().tolerance())
                       .gather(x, Vec3::UnitZ())
                       .irradiance.x();
  EXPECT_NEAR(traced(b.scene(), x, Vec3::UnitZ()), h, 1e-12);
}

/// The two exact methods agree within 1e-9 relative or 1e-12 absolute (per channel).
::testing::AssertionResult agree(const Rgb& vertex, const Rgb& hemisphere) {
  for (int c = 0; c < 3; ++c) {
    const double tolerance = std::max(1e-9 * std::abs(hemisphere[c]), 1e-12);
    if (!(std::abs(vertex[c] - hemisphere[c]) <= tolerance)) {
      return ::testing::AssertionFailure()
             << "channel " << c << ": vertex " << vertex[c] << " hemisphere " << hemisphere[c]
             << " (difference " << vertex[c] - hemisphere[c] << ")";
    }
  }
  return ::testing::AssertionSuccess();
}

/// Compares both methods at every site of a scene; counts what the tracer met.
struct Tally {
  int points = 0, disagreements = 0, conjunctive = 0, slow_path = 0, interpenetrating = 0,
      occluded = 0;
  int first_site_conjunctive = 0;  ///< Scenes whose first site traced a conjunctive cone
  void compare(const test::RandomScene& r, const std::string& label) {
    const VertexTracer tracer(r.scene);
    const HemisphereGatherer hemisphere(faces_from_polygons(r.scene), r.scene.tolerance());
    for (const auto& site : r.sites) {
      const bool first = &site == &r.sites.front();
      ++points;
      const VertexTraceResult v = tracer.gather(site.x, site.n);
      const HemisphereGather h = hemisphere.gather(site.x, site.n, true);
      conjunctive += v.conjunctive > 0;
      first_site_conjunctive += first && v.conjunctive > 0;
      slow_path += v.slow_path > 0;
      // Occluded: some polygon shows in more than one fragment or not whole (cheap proxy: a
      // fragment count above the polygon count).
      occluded += h.fragments.size() > r.scene.polygons.size();
      const auto result = agree(v.irradiance, h.irradiance);
      if (!result && ++disagreements <= 10)
        ADD_FAILURE() << label << " at " << site.x.transpose() << ": " << result.message();
    }
  }
};

TEST(VertexTracing, AgreesWithHemisphereOnRandomScenes) {
  Tally tally;
  for (uint64_t seed = 1; seed <= 2000; ++seed) {
    test::RandomSceneMaker maker(seed);
    const test::RandomScene r = maker.random_scene();
    tally.interpenetrating += !interpenetration_segments(r.scene).empty();
    tally.compare(r, "seed " + std::to_string(seed));
  }
  EXPECT_EQ(tally.disagreements, 0) << "of " << tally.points << " points";
  // The scenes exercise what they are meant to (counts printed for the record).
  std::cout << tally.points << " points, " << tally.interpenetrating
            << " of 2000 scenes interpenetrating, " << tally.occluded << " points with occlusion, "
            << tally.conjunctive << " with conjunctive cones\n";
  EXPECT_GT(tally.interpenetrating, 200);
  EXPECT_GT(tally.occluded, 1000);
}

TEST(VertexTracing, AgreesWithHemisphereOnConjunctiveFamilies) {
  const char* names[] = {"three_edges", "vertex_behind", "collinear_edges", "coplanar",
                         "vertex_on_edge"};
  for (int family = 0; family < test::RandomSceneMaker::kConjunctions; ++family) {
    Tally tally;
    for (uint64_t seed = 1; seed <= 200; ++seed) {
      test::RandomSceneMaker maker(1000 * (family + 1) + seed);
      const auto r =
          maker.conjunctive_scene(static_cast<test::RandomSceneMaker::Conjunction>(family));
      tally.compare(r, std::string(names[family]) + " seed " + std::to_string(seed));
    }
    EXPECT_EQ(tally.disagreements, 0) << names[family] << ": of " << tally.points << " points";
    std::cout << names[family] << ": " << tally.points << " points, " << tally.conjunctive
              << " with conjunctive cones, " << tally.slow_path << " took the slow path\n";
    // Seen from the origin (the first site) every family has a conjunctive vertex unless it is
    // hidden or culled (no emitter there); measured 99 (coplanar, whose T-junction is off the
    // shared direction) to 169 of 200.
    std::cout << "  from the origin: " << tally.first_site_conjunctive << " of 200\n";
    EXPECT_GT(tally.first_site_conjunctive, 80) << names[family];
  }
}

TEST(VertexTracing, EmitterCullingChangesNothing) {
  // 001 §4.1: tracing only where an emitter shows must give the general path's value.
  VertexTracer::Options everything;
  everything.cull_to_emitters = false;
  int traced_culled = 0, traced_all = 0;
  for (uint64_t seed = 1; seed <= 300; ++seed) {
    test::RandomSceneMaker maker(seed);
    const test::RandomScene r = maker.random_scene();
    const VertexTracer tracer(r.scene);
    for (const auto& site : r.sites) {
      const VertexTraceResult fast = tracer.gather(site.x, site.n);
      const VertexTraceResult general = tracer.gather(site.x, site.n, everything);
      traced_culled += fast.traced;
      traced_all += general.traced;
      for (int c = 0; c < 3; ++c) {
        ASSERT_NEAR(fast.irradiance[c], general.irradiance[c],
                    1e-13 * std::max(1.0, std::abs(general.irradiance[c])))
            << "seed " << seed;
      }
    }
  }
  EXPECT_LT(traced_culled, traced_all);  // and it does cull
}

/// Both methods at points on the surfaces of `scene` (every fifth on an edge or at a vertex),
/// every leaf element of a coarse solution emitting its radiosity (001 §4.2).
int radiosity_disagreements(const std::string& name, int points) {
  const test::SolvedScene solved = test::solve_coarse(name);
  const Scene& scene = solved.scene;
  const auto& faces = solved.faces;
  EXPECT_GT(faces.size(), 50u);
  const VertexTracer tracer(scene, faces);
  const HemisphereGatherer hemisphere(faces, scene.tolerance());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  int disagreements = 0;
  for (int i = 0; i < points; ++i) {
    const Polygon& p = scene.polygons[static_cast<size_t>(u(rng) * scene.polygons.size())];
    const double a = i % 5 == 0 ? std::round(u(rng)) : u(rng),
                 b = i % 5 == 0 ? 0.0 : u(rng) * (1 - a);
    const Vec3 x =
        p.vertices[0] + a * (p.vertices[1] - p.vertices[0]) + b * (p.vertices[2] - p.vertices[0]);
    const auto result =
        agree(tracer.gather(x, p.normal).irradiance, hemisphere.gather(x, p.normal).irradiance);
    if (!result && ++disagreements <= 5)
      ADD_FAILURE() << name << " at " << x.transpose() << ": " << result.message();
  }
  return disagreements;
}

TEST(VertexTracing, AgreesWithHemisphereInRadiosityEnvironments) {
  EXPECT_EQ(radiosity_disagreements("closed-cube", 60), 0);
  EXPECT_EQ(radiosity_disagreements("light-over-floor", 60), 0);
  // Clipped at a small height instead of the image square, far walls showed under the blocks
  // that stand on the floor: 12 of these 300 disagreed.
  EXPECT_EQ(radiosity_disagreements("cornell-box", 300), 0);
}

/// Both methods on polygons that all emit 1, at x with normal n.
::testing::AssertionResult methods_agree(const std::vector<std::vector<Vec3>>& polygons,
                                         const Vec3& x, const Vec3& n) {
  SceneBuilder b;
  const int lamp = b.material("lamp", Rgb::Zero(), Rgb::Ones());
  for (const auto& p : polygons) b.polygon(p, lamp);
  return agree(VertexTracer(b.scene()).gather(x, n).irradiance,
               HemisphereGatherer(faces_from_polygons(b.scene()), b.scene().tolerance())
                   .gather(x, n)
                   .irradiance);
}

TEST(VertexTracing, RegressionVertexOnTheTangentPlane) {
  // A polygon vertex exactly in the receiver's tangent plane: its two horizon-clip points fall
  // in one cone and the edges leaving it are parallel in the image but different planes. Was
  // -0.0388 for 0.1054 when boundaries were ordered by direction alone.
  EXPECT_TRUE(methods_agree({{{1, 0, 0}, {0.99, -1, 0}, {0.98, -1, 1}}}, Vec3(0.6, 0, 0.4),
                            Vec3(0, -1, 0)));
}

// The Cornell box's left wall, twisted by 3.2 mm, as the loader splits it: two triangles.
const std::vector<Vec3> kTwistedWallLower = {{556, 548.8, 0}, {552.8, 0, 0}, {549.6, 0, 559.2}};
const std::vector<Vec3> kTwistedWallUpper = {
    {549.6, 0, 559.2}, {556, 548.8, 559.2}, {556, 548.8, 0}};

TEST(VertexTracing, RegressionTwistedWallFromTheCeiling) {
  // The Cornell box's split left wall seen from the ceiling: both triangles touch the tangent
  // plane. Nearly parallel features through one cone merged it with a far crossing (-0.022
  // for 0.239); merges now only take candidates near the cone.
  EXPECT_TRUE(methods_agree({kTwistedWallLower, kTwistedWallUpper}, Vec3(338.84, 548.8, 234.899),
                            Vec3(0, -1, 0)));
}

// The next three were found by probing the Cornell box with every polygon emitting (40 of 2000
// surface points disagreed); all are polygons touching the receiver's tangent plane.
TEST(VertexTracing, RegressionCornellRightWallAndTwistedWallFromTheCeiling) {
  // A horizon edge ~1e-9 long had a plane known to ~1e-5: its crossing with the shared edge
  // landed 3e-6 (relative) beyond its end and passed an angular end test (0.387 for 0.496).
  // Crossings and edge spans are now tested against the edge's image segment.
  EXPECT_TRUE(methods_agree({{{0, 0, 559.2}, {0, 0, 0}, {0, 548.8, 0}, {0, 548.8, 559.2}},
                             kTwistedWallLower,
                             kTwistedWallUpper},
                            Vec3(526.95159062917264, 548.79999999999995, 75.676727710292852),
                            Vec3(0, -1, 0)));
}

TEST(VertexTracing, RegressionTwistedWallSeenFromBehindNextToTheCeiling) {
  // One triangle is seen from behind and hidden by the other, which shares its edge. Their
  // equal-depth plane from the plane equations (cancellation ~1e-14) put its line on the wrong
  // side of a sliver at the horizon vertex, and the side was tested through q, not where the
  // boundaries were ordered (0.50372 for 0.50471).
  EXPECT_TRUE(methods_agree({kTwistedWallLower, kTwistedWallUpper},
                            Vec3(555.57165961082535, 548.79999999999995, 235.97582425503953),
                            Vec3(0, -1, 0)));
}

TEST(VertexTracing, RegressionBackWallAndTwistedWallFromTheFloor) {
  // Two cut points 1.4e-10 apart (relative) in separate cones; the cut edge between them had a
  // plane from two nearby points, so the crossing that would merge the cones was lost (0.2449
  // for 0.2469). The cut edge now takes the square's exact plane.
  EXPECT_TRUE(
      methods_agree({{{549.6, 0, 559.2}, {0, 0, 559.2}, {0, 548.8, 559.2}, {556, 548.8, 559.2}},
                     kTwistedWallUpper},
                    Vec3(549.64004334006722, 0, 552.20242632326551), Vec3(0, 1, 0)));
}

TEST(VertexTracing, AgreesWithHemisphereInTheCornellBoxWithEveryPolygonEmitting) {
  // Many polygons touch one another's tangent planes here. Points on random polygons, 15% on
  // an edge and 5% at a vertex.
  const Scene scene =
      load_scene(std::filesystem::path(RAD_SOURCE_DIR) / "data/cornell-box/scene.json");
  const std::vector<Rgb> ones(scene.polygons.size(), Rgb::Ones());
  const VertexTracer tracer(scene, faces_from_polygons(scene, ones));
  const HemisphereGatherer hemisphere(faces_from_polygons(scene, ones), scene.tolerance());
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(0, 1);
  int disagreements = 0;
  for (int i = 0; i < 2000; ++i) {
    const Polygon& p =
        scene.polygons[static_cast<size_t>(u(rng) * scene.polygons.size()) % scene.polygons.size()];
    const Vec3 x = test::random_surface_point(p, rng, 0.05, 0.15);
    const auto result =
        agree(tracer.gather(x, p.normal).irradiance, hemisphere.gather(x, p.normal).irradiance);
    if (!result && ++disagreements <= 5)
      ADD_FAILURE() << "at " << x.transpose() << ": " << result.message();
  }
  EXPECT_EQ(disagreements, 0);
}

TEST(VertexTracing, DegenerateClasses) {
  SceneBuilder b;
  const int lamp = b.material("lamp", Rgb::Zero(), Rgb::Ones());
  const int grey = b.material("grey", Rgb::Constant(0.5), Rgb::Zero());
  b.rectangle(-1, 1, -1, 1, 1, true, lamp);
  b.rectangle(0, 0.5, 0, 0.5, 0.5, true, grey);  // x below one of its corners
  b.polygon({{0.2, -0.6, 0.3}, {0.2, -0.2, 0.3}, {0.2, -0.4, 0.9}},
            grey);  // in a plane through (0.2, y, z)
  b.rectangle(-0.3, -0.3 + 1e-7, 0.1, 0.1 + 1e-7, 0.6, true, grey);         // tiny
  b.polygon({{-1e3, -1e3, 1.5}, {1e3, -1e3, 1.5}, {1e3, 1e3, 1.5}}, grey);  // huge, behind the lamp
  b.rectangle(-2, 2, -2, 2, 0, false, grey);  // the receiver's own floor
  const HemisphereGatherer hemisphere(faces_from_polygons(b.scene()), b.scene().tolerance());
  const VertexTracer tracer(b.scene());
  for (const Vec3& x : {Vec3(0, 0, 0), Vec3(0.2, -0.4, 0), Vec3(0.5, 0.5, 0), Vec3(-1, 0, 0),
                        Vec3(0.2, -0.4, 0.3)}) {
    EXPECT_TRUE(agree(tracer.gather(x, Vec3::UnitZ()).irradiance,
                      hemisphere.gather(x, Vec3::UnitZ()).irradiance))
        << x.transpose();
  }
  // Seen edge-on from a point in the blocker's plane (x = 0.2), and from a point on a lamp edge.
  const Vec3 side(1, 0, 0);
  EXPECT_TRUE(agree(tracer.gather(Vec3(0.2, -0.4, 0.5), side).irradiance,
                    hemisphere.gather(Vec3(0.2, -0.4, 0.5), side).irradiance));
  EXPECT_TRUE(agree(tracer.gather(Vec3(1, 0, 1), -side).irradiance,
                    hemisphere.gather(Vec3(1, 0, 1), -side).irradiance));
}

}  // namespace
}  // namespace rad
