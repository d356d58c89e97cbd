// Shaft culling must change nothing: the local pass at tolerance 0 (unoccluded faces by
// Lambert's formula, the rest gathered with only the faces that may hide them) against the
// plain gatherers over every face, on scenes built to break it.
#include "localpass/occlusion_culling.h"

#include <gtest/gtest.h>

#include <random>

#include "hemisphere/hemisphere_gatherer.h"
#include "localpass/local_pass.h"
#include "tests/coarse_solution.h"
#include "tests/random_scenes.h"
#include "tests/surface_points.h"
#include "vertex/vertex_tracer.h"

namespace rad {
namespace {

using test::radiating_faces;

::testing::AssertionResult same(const Rgb& culled, const Rgb& plain) {
  for (int c = 0; c < 3; ++c) {
    if (!(std::abs(culled[c] - plain[c]) <= 1e-10 * std::max(1.0, std::abs(plain[c])))) {
      return ::testing::AssertionFailure()
             << "culled " << culled.transpose() << " plain " << plain.transpose();
    }
  }
  return ::testing::AssertionSuccess();
}

/// The local pass at tolerance 0 against the plain gather of the same method at every site.
struct Differential {
  int points = 0, failures = 0, culled_points = 0;
  void compare(const Scene& scene, const std::vector<EmittingFace>& faces,
               const std::vector<test::ProbeSite>& sites, const std::string& label) {
    const HemisphereGatherer hemisphere(faces, scene.tolerance());
    const VertexTracer tracer(scene, faces);
    const LocalPass hemisphere_pass(scene, faces, Method::hemisphere);
    const LocalPass vertex_pass(scene, faces, Method::vertex);
    for (const test::ProbeSite& s : sites) {
      ++points;
      const LocalPassResult h = hemisphere_pass.gather(s.x, s.n, 0),
                            v = vertex_pass.gather(s.x, s.n, 0);
      culled_points += h.unoccluded > 0;
      const auto hs = same(h.irradiance, hemisphere.gather(s.x, s.n).irradiance);
      const auto vs = same(v.irradiance, tracer.gather(s.x, s.n).irradiance);
      if ((!hs || !vs) && ++failures <= 10) {
        ADD_FAILURE() << label << " at " << s.x.transpose() << ": hemisphere " << hs.message()
                      << "; vertex " << vs.message();
      }
    }
  }
};

TEST(OcclusionCulling, ChangesNothingOnRandomScenes) {
  // Random, concave and interpenetrating polygons over a floor, every one radiating.
  Differential d;
  for (uint64_t seed = 1; seed <= 300; ++seed) {
    test::RandomSceneMaker maker(seed);
    const test::RandomScene r = maker.random_scene();
    d.compare(r.scene, radiating_faces(r.scene, seed), r.sites, "seed " + std::to_string(seed));
  }
  EXPECT_EQ(d.failures, 0) << "of " << d.points << " points";
  // The culling did take faces out (measured: at 197 of 1,800 points; these scenes are cluttered).
  EXPECT_GT(d.culled_points, d.points / 10);
}

TEST(OcclusionCulling, ChangesNothingOnTheDegenerateFamilies) {
  // Coplanar overlaps, vertices on edges, collinear edges, conjunctions behind.
  for (int family = 0; family < test::RandomSceneMaker::kConjunctions; ++family) {
    Differential d;
    for (uint64_t seed = 1; seed <= 60; ++seed) {
      test::RandomSceneMaker maker(1000 * (family + 1) + seed);
      const auto r =
          maker.conjunctive_scene(static_cast<test::RandomSceneMaker::Conjunction>(family));
      d.compare(r.scene, radiating_faces(r.scene, seed), r.sites,
                "family " + std::to_string(family) + " seed " + std::to_string(seed));
    }
    EXPECT_EQ(d.failures, 0) << "family " << family << ": of " << d.points << " points";
  }
}

TEST(OcclusionCulling, ChangesNothingOnTheCornellSolution) {
  // The coarse solution's elements, at points on the surfaces: 10% at polygon vertices (room
  // corners, block corners on the floor), 20% on edges.
  const test::SolvedScene& s = test::coarse_cornell();
  std::mt19937_64 rng(11);
  std::vector<test::ProbeSite> sites;
  for (int i = 0; i < 150; ++i) {
    const Polygon& p = s.scene.polygons[static_cast<size_t>(rng() % s.scene.polygons.size())];
    sites.push_back({test::random_surface_point(p, rng, 0.1, 0.2), p.normal});
  }
  Differential d;
  d.compare(s.scene, s.faces, sites, "cornell");
  EXPECT_EQ(d.failures, 0) << "of " << d.points << " points";
}

TEST(OcclusionCulling, NothingInsideAClosedCubeIsOccluded) {
  // A convex room: from inside, every element is seen whole, so the exact pass needs no
  // visibility work at all. (Not so in the Cornell box: its left wall is folded into a ridge,
  // whose two triangles do hide slivers of each other.)
  const test::SolvedScene s = test::solve_coarse("closed-cube");
  const LocalPass pass(s.scene, s.faces, Method::hemisphere);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.01, 0.99);
  std::normal_distribution<double> g;
  for (int i = 0; i < 200; ++i) {
    const LocalPassResult r =
        pass.gather(Vec3(u(rng), u(rng), u(rng)), Vec3(g(rng), g(rng), g(rng)).normalized(), 0);
    EXPECT_EQ(r.projected, 0);  // no visibility query, no gather
    EXPECT_EQ(r.gathers, 0);
    EXPECT_GT(r.unoccluded, 0);
    EXPECT_EQ(r.unoccluded, r.gathered_exactly);
  }
}

}  // namespace
}  // namespace rad
