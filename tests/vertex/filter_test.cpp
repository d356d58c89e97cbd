// Filters (paper 000 §2.2) in vertex tracing: against Howell's closed forms, and against an
// identity that uses only the opaque hemisphere gatherer (which knows nothing of filters).
#include <gtest/gtest.h>

#include <random>

#include "hemisphere/hemisphere_gatherer.h"
#include "scene/polygon_faces.h"
#include "tests/closed_forms.h"
#include "tests/filter_identity.h"
#include "tests/random_scenes.h"
#include "tests/rgb_checks.h"
#include "tests/scene_builder.h"
#include "vertex/vertex_tracer.h"

namespace rad {
namespace {

using test::agree;
using test::by_subsets;
using test::make_filters;
using test::random_transmittance;
using test::SceneBuilder;

/// "prefix<i>" (appended, not by operator+: GCC 12 warns falsely of overlapping copies there).
std::string numbered(const char* prefix, size_t i) {
  std::string name = prefix;
  name += std::to_string(i);
  return name;
}

Rgb traced(const Scene& scene, const Vec3& x, const Vec3& n) {
  return VertexTracer(scene).gather(x, n).irradiance;
}

/// Each face split into triangles from its centroid, each radiating its own random exitance:
/// faces like a solution's elements, whose inner edges separate different radiosities (on
/// filters too, so a filter's inner edges and those behind it are both seen).
std::vector<EmittingFace> fan_elements(const Scene& scene, test::RandomSceneMaker& maker) {
  std::vector<EmittingFace> out;
  for (const EmittingFace& f : faces_from_polygons(scene)) {
    Vec3 centre = Vec3::Zero();
    for (const Vec3& v : f.vertices) centre += v;
    centre /= static_cast<double>(f.vertices.size());
    for (size_t i = 0; i < f.vertices.size(); ++i) {
      EmittingFace t = f;
      t.vertices = {centre, f.vertices[i], f.vertices[(i + 1) % f.vertices.size()]};
      t.on_boundary = {false, f.on_boundary[i], false};
      t.exitance = Rgb(maker.uniform(0, 2), maker.uniform(0, 2), maker.uniform(0, 2));
      out.push_back(std::move(t));
    }
  }
  return out;
}

TEST(Filters, WholeLampBehindAFilterIsTransmittanceTimesHowellB3) {
  // The filter covers the lamp as seen from x, front or back towards x: T x E x B-3.
  const Rgb transmittance(0.2, 0.55, 0.9);
  for (const auto& c : test::kHowellB3) {
    for (const bool filter_faces_x : {true, false}) {
      SceneBuilder b;
      const int lamp = b.material("lamp", Rgb::Zero(), Rgb::Ones());
      const int glass = b.material("glass", Rgb::Constant(0.05), Rgb::Zero(), transmittance);
      b.rectangle(0, c.a, 0, c.b, c.c, true, lamp);
      b.rectangle(-1, c.a + 1, -1, c.b + 1, c.c / 2, filter_faces_x, glass);
      EXPECT_TRUE(agree(traced(b.scene(), Vec3::Zero(), Vec3::UnitZ()), c.F * transmittance, 1e-12))
          << "B-3 (" << c.a << ", " << c.b << ", " << c.c << "), filter facing x "
          << filter_faces_x;
    }
  }
}

TEST(Filters, StackedFiltersMultiply) {
  // Three filters over the whole lamp, in any order of depth: the product of the three.
  const Rgb t1(0.9, 0.5, 0.1), t2(0.3, 0.7, 1.0), t3(0.6, 0.6, 0.6);
  SceneBuilder b;
  const int lamp = b.material("lamp", Rgb::Zero(), Rgb(2, 3, 4));
  b.rectangle(0, 1, 0, 2, 3, true, lamp);
  b.rectangle(-2, 3, -2, 4, 0.5, true, b.material("a", Rgb::Zero(), Rgb::Zero(), t1));
  b.rectangle(-2, 3, -2, 4, 2.5, false, b.material("b", Rgb::Zero(), Rgb::Zero(), t2));
  b.rectangle(-2, 3, -2, 4, 1.2, true, b.material("c", Rgb::Zero(), Rgb::Zero(), t3));
  const Rgb expected =
      test::howell_b3(1, 2, 3) * Rgb(2, 3, 4).cwiseProduct(t1).cwiseProduct(t2).cwiseProduct(t3);
  EXPECT_TRUE(agree(traced(b.scene(), Vec3::Zero(), Vec3::UnitZ()), expected, 1e-12));
}

TEST(Filters, EdgeCollinearWithALampEdgeSeenFromX) {
  // 000 Fig. 7a: a filter edge coplanar with a source edge through x. The filter at z = 1 ends
  // at y = 0.5, which x = 0 sees on the lamp's edge y = 1 at z = 2; it covers x <= 0.5 of the
  // lamp (its edge x = 0.25), so T F(left half) + F(right half).
  const Rgb t(0.25, 0.5, 0.75);
  SceneBuilder b;
  const int lamp = b.material("lamp", Rgb::Zero(), Rgb::Ones());
  b.rectangle(0, 1, 0, 1, 2, true, lamp);
  b.rectangle(-1, 0.25, -1, 0.5, 1, true, b.material("glass", Rgb::Zero(), Rgb::Zero(), t));
  const Rgb expected = test::howell_rectangle(0, 0.5, 0, 1, 2) * t +
                       Rgb::Constant(test::howell_rectangle(0.5, 1, 0, 1, 2));
  EXPECT_TRUE(agree(traced(b.scene(), Vec3::Zero(), Vec3::UnitZ()), expected, 1e-12));
}

TEST(Filters, CoplanarOverlappingFiltersComposeWhereTheyOverlap) {
  // Two filters in one plane, overlapping over x in [0.2, 0.5] of the lamp as seen from x:
  // there the light passes both (T_a T_b), elsewhere one.
  const Rgb ta(0.3, 0.6, 0.9), tb(0.8, 0.4, 0.5);
  SceneBuilder b;
  const int lamp = b.material("lamp", Rgb::Zero(), Rgb::Ones());
  b.rectangle(0, 1, 0, 1, 2, true, lamp);
  b.rectangle(-1, 0.25, -1, 2, 1, true, b.material("a", Rgb::Zero(), Rgb::Zero(), ta));
  b.rectangle(0.1, 2, -1, 2, 1, true, b.material("b", Rgb::Zero(), Rgb::Zero(), tb));
  const Rgb expected = test::howell_rectangle(0, 0.2, 0, 1, 2) * ta +
                       test::howell_rectangle(0.2, 0.5, 0, 1, 2) * ta.cwiseProduct(tb) +
                       test::howell_rectangle(0.5, 1, 0, 1, 2) * tb;
  EXPECT_TRUE(agree(traced(b.scene(), Vec3::Zero(), Vec3::UnitZ()), expected, 1e-12));
}

TEST(Filters, InTheReceiversPlaneOrEdgeOnTheyChangeNothing) {
  // A filter in x's tangent plane (beside x, and under x) and one edge-on (its plane through
  // x): neither has solid angle, so the lamp is seen whole: E x B-3.
  const Rgb t(0.1, 0.2, 0.3);
  SceneBuilder b;
  const int lamp = b.material("lamp", Rgb::Zero(), Rgb::Ones());
  const int glass = b.material("glass", Rgb::Zero(), Rgb::Zero(), t);
  b.rectangle(0, 2, 0, 3, 1, true, lamp);
  b.rectangle(0.5, 1.5, 0.5, 1.5, 0, false, glass);   // beside x, in its plane
  b.rectangle(-0.5, 0.5, -0.5, 0.5, 0, true, glass);  // x on it (its back)
  b.polygon({{0, -1, 0.2}, {0, 2, 0.2}, {0, 2, 0.9}, {0, -1, 0.9}}, glass);  // edge-on
  EXPECT_TRUE(agree(traced(b.scene(), Vec3::Zero(), Vec3::UnitZ()),
                    Rgb::Constant(test::howell_b3(2, 3, 1)), 1e-12));
}

TEST(Filters, OneChannelOpaqueOneClearEqualsTheOpaqueAndTheRemovedScene) {
  // Transmittance (0, 0.5, 1): channel 0 must be the scene with the polygon opaque, channel 2
  // the scene without it (it emits nothing), through the filter path of the code in both.
  test::RandomSceneMaker maker(17);
  int compared = 0, changed = 0;
  for (int s = 0; s < 30; ++s) {
    test::RandomScene r = maker.random_scene();
    std::vector<int> grey;
    for (size_t p = 1; p < r.scene.polygons.size(); ++p) {
      if (!r.scene.materials[r.scene.polygons[p].material].is_emitter())
        grey.push_back(static_cast<int>(p));
    }
    if (grey.empty()) continue;
    Scene filtered = r.scene, removed = r.scene;
    filtered.materials.push_back(Material{"f", Rgb::Zero(), Rgb::Zero(), Rgb(0, 0.5, 1)});
    filtered.polygons[grey[0]].material = static_cast<int>(filtered.materials.size()) - 1;
    removed.polygons.erase(removed.polygons.begin() + grey[0]);
    for (const test::ProbeSite& site : r.sites) {
      const Rgb f = traced(filtered, site.x, site.n);
      const Rgb opaque = traced(r.scene, site.x, site.n), clear = traced(removed, site.x, site.n);
      EXPECT_TRUE(agree(Rgb::Constant(f[0]), Rgb::Constant(opaque[0]))) << "scene " << s;
      EXPECT_TRUE(agree(Rgb::Constant(f[2]), Rgb::Constant(clear[2]))) << "scene " << s;
      ++compared;
      changed += std::abs(opaque[2] - clear[2]) > 1e-6 * std::max(clear[2], 1e-12);
    }
  }
  EXPECT_GT(compared, 60);
  EXPECT_GT(changed, 10);  // the polygon did hide something in many of them
}

/// Compares vertex tracing with the subset identity at every site; returns sites where the
/// filters mattered (the all-opaque value differs), counting disagreements.
struct FilterTally {
  int sites = 0, mattered = 0, disagreements = 0;
  void compare(const Scene& scene, const std::vector<int>& filters,
               const std::vector<test::ProbeSite>& sites_, const std::string& label,
               std::vector<EmittingFace> faces = {}) {
    if (filters.empty()) return;
    if (faces.empty()) faces = faces_from_polygons(scene);
    const VertexTracer tracer(scene, faces);
    std::vector<EmittingFace> opaque = faces;
    for (EmittingFace& f : opaque) f.transmittance = Rgb::Zero();
    const HemisphereGatherer all_opaque(opaque, scene.tolerance());
    for (const test::ProbeSite& site : sites_) {
      ++sites;
      const Rgb v = tracer.gather(site.x, site.n).irradiance;
      const Rgb expected = by_subsets(scene, faces, filters, site.x, site.n);
      const Rgb closed = all_opaque.gather(site.x, site.n).irradiance;
      mattered += (expected - closed).cwiseAbs().maxCoeff() > 1e-6 * expected.maxCoeff();
      const auto ok = agree(v, expected);
      if (!ok && ++disagreements <= 5) {
        ADD_FAILURE() << label << " with " << filters.size() << " filters at x "
                      << site.x.transpose() << " n " << site.n.transpose() << ": " << ok.message();
      }
    }
  }
};

TEST(Filters, RandomScenesMatchTheSubsetIdentity) {
  // The general family with its non-emitting polygons turned into filters: random positions,
  // orientations, concave ones, interpenetrating at will; sites on the floor and on polygons
  // (on filters too).
  test::RandomSceneMaker maker(2000);
  FilterTally tally;
  for (int s = 0; s < 60; ++s) {
    test::RandomScene r = maker.random_scene();
    const std::vector<int> filters = make_filters(r.scene, maker, 8);
    tally.compare(r.scene, filters, r.sites, numbered("random scene ", static_cast<size_t>(s)));
  }
  EXPECT_EQ(tally.disagreements, 0);
  EXPECT_GT(tally.sites, 100);
  EXPECT_GT(tally.mattered, 40);
}

TEST(Filters, ManyFiltersOverALampMatchTheSubsetIdentity) {
  // k = 1..8 random filters (tilted, concave, crossing each other) between a floor and a lamp,
  // plus an opaque blocker: up to 2^8 opaque gathers per point.
  test::RandomSceneMaker maker(2001);
  FilterTally tally;
  for (int k = 1; k <= 8; ++k) {
    SceneBuilder b;
    const int grey = b.material("grey", Rgb::Constant(0.5), Rgb::Zero());
    b.rectangle(-2, 2, -2, 2, 0, false, grey);
    b.rectangle(-0.8, 0.6, -0.5, 0.9, 2, true, b.material("lamp", Rgb::Zero(), Rgb(1, 2, 3)));
    for (int i = 0; i < k; ++i) {
      Vec3 n = maker.unit();
      if (std::abs(n.z()) < 0.3) n.z() = 0.3;
      const int filter = b.material(numbered("f", static_cast<size_t>(i)), Rgb::Zero(), Rgb::Zero(),
                                    random_transmittance(maker));
      b.polygon(maker.polygon(Vec3(maker.uniform(-0.5, 0.5), maker.uniform(-0.5, 0.5),
                                   maker.uniform(0.3, 1.7)),
                              n.normalized(), maker.uniform(0.3, 0.9)),
                filter);
    }
    b.polygon(maker.polygon(Vec3(0.2, 0.1, 1.0), maker.unit(), 0.25), grey);  // the blocker
    const Scene& scene = b.scene();
    std::vector<int> filters;
    for (size_t p = 0; p < scene.polygons.size(); ++p) {
      if (scene.materials[scene.polygons[p].material].is_filter())
        filters.push_back(static_cast<int>(p));
    }
    std::vector<test::ProbeSite> sites;
    for (int i = 0; i < 6; ++i)
      sites.push_back({Vec3(maker.uniform(-1, 1), maker.uniform(-1, 1), 0), Vec3::UnitZ()});
    tally.compare(scene, filters, sites, numbered("k = ", static_cast<size_t>(k)));
  }
  EXPECT_EQ(tally.disagreements, 0);
  EXPECT_GT(tally.mattered, 30);
}

TEST(Filters, ConjunctiveFamiliesMatchTheSubsetIdentity) {
  // The degenerate families of vertex tracing (three edges through one apparent point, vertices
  // behind one another, collinear edges, coplanar overlapping polygons, a vertex on an edge),
  // with their non-emitting polygons as filters: apparent crossings of filter edges are real
  // vertices of the visible map now.
  test::RandomSceneMaker maker(2002);
  FilterTally tally;
  for (int s = 0; s < 40; ++s) {
    const auto kind =
        static_cast<test::RandomSceneMaker::Conjunction>(s % test::RandomSceneMaker::kConjunctions);
    test::RandomScene r = maker.conjunctive_scene(kind);
    const std::vector<int> filters = make_filters(r.scene, maker, 8);
    tally.compare(r.scene, filters, r.sites,
                  numbered("conjunctive family ", static_cast<size_t>(s % 5)));
  }
  EXPECT_EQ(tally.disagreements, 0);
  EXPECT_GT(tally.mattered, 10);
}

TEST(Filters, ElementsOnAndBehindFiltersMatchTheSubsetIdentity) {
  // Radiosity reconstruction (001 §4.2): every element radiates, filters too, and the inner
  // edges of a filter and of what shows through it cross into real vertices of the visible map.
  test::RandomSceneMaker maker(2003);
  FilterTally tally;
  for (int s = 0; s < 25; ++s) {
    test::RandomScene r = maker.random_scene();
    const std::vector<int> filters = make_filters(r.scene, maker, 5);
    tally.compare(r.scene, filters, r.sites, numbered("elements of random scene ", s),
                  fan_elements(r.scene, maker));
  }
  EXPECT_EQ(tally.disagreements, 0);
  EXPECT_GT(tally.mattered, 40);
}

}  // namespace
}  // namespace rad
