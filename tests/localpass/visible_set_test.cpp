// The visibility culling (localpass/visible_set.h) must change nothing: the local pass over what
// a point may see against the plain gatherers over every face, at tolerance 0, and its bound at
// a tolerance; and it must pass over what walls hide. Rooms with doors between them, furniture,
// and seeded random scenes, with the culling forced on (visible_set_from = 0).
#include "localpass/visible_set.h"

#include <gtest/gtest.h>

#include <random>

#include "hemisphere/hemisphere_gatherer.h"
#include "localpass/local_pass.h"
#include "tests/random_scenes.h"
#include "tests/scene_builder.h"
#include "vertex/vertex_tracer.h"

namespace rad {
namespace {

using test::radiating_faces;

/// A quad with the given corners' order (counter-clockwise from its front).
void quad(test::SceneBuilder& b, const Vec3& a, const Vec3& c, const Vec3& d, const Vec3& e,
          int material) {
  b.polygon({a, c, d, e}, material);
}

/// A row of rooms along x (each 1 x 1 x 1, fronts facing in), a door 0.3 wide and 0.6 high in
/// each wall between two rooms (that wall in four pieces round it), and `furniture` small boxes
/// in each room at seeded places. Room k spans x in [k, k + 1].
Scene rooms_with_doors(int rooms, int furniture, uint64_t seed) {
  test::SceneBuilder b;
  const int white = b.material("white", Rgb::Constant(0.5), Rgb::Zero());
  const double length = rooms;
  // Floor, ceiling, the two long walls and the two ends, facing in.
  quad(b, {0, 0, 0}, {0, 0, 1}, {length, 0, 1}, {length, 0, 0}, white);  // floor, up
  quad(b, {0, 1, 0}, {length, 1, 0}, {length, 1, 1}, {0, 1, 1}, white);  // ceiling, down
  quad(b, {0, 0, 0}, {length, 0, 0}, {length, 1, 0}, {0, 1, 0}, white);  // z = 0, facing +z
  quad(b, {0, 0, 1}, {0, 1, 1}, {length, 1, 1}, {length, 0, 1}, white);  // z = 1, facing -z
  quad(b, {0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, white);            // x = 0, facing +x
  quad(b, {length, 0, 0}, {length, 0, 1}, {length, 1, 1}, {length, 1, 0}, white);
  // The walls between: a door at z in [0.35, 0.65], y in [0, 0.6]; each piece facing -x (the
  // other side is its back: opaque from both).
  for (int k = 1; k < rooms; ++k) {
    const double x = k;
    const auto piece = [&](double z0, double z1, double y0, double y1) {
      quad(b, {x, y0, z0}, {x, y0, z1}, {x, y1, z1}, {x, y1, z0}, white);
    };
    piece(0, 0.35, 0, 1);
    piece(0.65, 1, 0, 1);
    piece(0.35, 0.65, 0.6, 1);
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.1, 0.8);
  for (int k = 0; k < rooms; ++k) {
    for (int i = 0; i < furniture; ++i) {
      const Vec3 lo(k + u(rng), 0, u(rng));
      b.box(lo, lo + Vec3(0.1, 0.05 + 0.3 * u(rng), 0.1), white);
    }
  }
  return b.scene();
}

/// At tolerance 0, the culled pass against the plain gatherers; at tolerance 0.05, its bound.
struct Checks {
  int points = 0, failures = 0, culled = 0;
  void run(const Scene& scene, const std::vector<EmittingFace>& faces,
           const std::vector<test::ProbeSite>& sites, const std::string& label) {
    LocalPassSettings settings;
    settings.visible_set_from = 0;
    const HemisphereGatherer hemisphere(faces, scene.tolerance());
    const VertexTracer tracer(scene, faces);
    const LocalPass hemisphere_pass(scene, faces, Method::hemisphere, settings);
    const LocalPass vertex_pass(scene, faces, Method::vertex, settings);
    for (const test::ProbeSite& s : sites) {
      ++points;
      const Rgb plain_h = hemisphere.gather(s.x, s.n).irradiance;
      const Rgb plain_v = tracer.gather(s.x, s.n).irradiance;
      const LocalPassResult h = hemisphere_pass.gather(s.x, s.n, 0);
      const LocalPassResult v = vertex_pass.gather(s.x, s.n, 0);
      const LocalPassResult bounded = hemisphere_pass.gather(s.x, s.n, 0.05);
      culled += h.visible_polygons < static_cast<int>(scene.polygons.size());
      const double scale = std::max(1.0, plain_h.maxCoeff());
      const bool exact_h = (h.irradiance - plain_h).cwiseAbs().maxCoeff() <= 1e-10 * scale;
      const bool exact_v = (v.irradiance - plain_v).cwiseAbs().maxCoeff() <= 1e-10 * scale;
      const bool within =
          ((bounded.irradiance - plain_h).cwiseAbs() - bounded.bound).maxCoeff() <= 1e-12 * scale;
      if ((!exact_h || !exact_v || !within) && ++failures <= 10) {
        ADD_FAILURE() << label << " at " << s.x.transpose() << ": plain " << plain_h.transpose()
                      << ", culled hemisphere " << h.irradiance.transpose() << ", vertex "
                      << v.irradiance.transpose() << ", at 0.05 " << bounded.irradiance.transpose()
                      << " +- " << bounded.bound.transpose();
      }
    }
  }
};

/// Points on the floor and on the furniture's tops, in every room, facing up, and a few on the
/// walls.
std::vector<test::ProbeSite> room_sites(int rooms, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.02, 0.98);
  std::vector<test::ProbeSite> sites;
  for (int k = 0; k < rooms; ++k) {
    for (int i = 0; i < 6; ++i) sites.push_back({Vec3(k + u(rng), 0, u(rng)), Vec3::UnitY()});
    sites.push_back({Vec3(k + u(rng), u(rng), 0), Vec3::UnitZ()});
    sites.push_back({Vec3(k + u(rng), 1, u(rng)), -Vec3::UnitY()});
  }
  // On the door's edges and in the doorway's plane (the wall pieces' shared lines).
  sites.push_back({Vec3(1, 0, 0.35), Vec3::UnitY()});
  sites.push_back({Vec3(1, 0, 0.5), Vec3::UnitY()});
  return sites;
}

TEST(VisibleSet, ChangesNothingInRoomsWithDoorsAndFurniture) {
  Checks c;
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    const Scene scene = rooms_with_doors(4, 6, seed);
    c.run(scene, radiating_faces(scene, seed), room_sites(4, seed),
          "rooms " + std::to_string(seed));
  }
  EXPECT_EQ(c.failures, 0) << "of " << c.points << " points";
  EXPECT_GT(c.culled, c.points / 2) << "the culling must leave polygons out";
}

TEST(VisibleSet, ChangesNothingOnRandomScenes) {
  // Random, concave and interpenetrating polygons over a floor; and the degenerate families.
  Checks c;
  for (uint64_t seed = 1; seed <= 150; ++seed) {
    test::RandomSceneMaker maker(seed);
    const test::RandomScene r = maker.random_scene();
    c.run(r.scene, radiating_faces(r.scene, seed), r.sites, "seed " + std::to_string(seed));
  }
  for (int family = 0; family < test::RandomSceneMaker::kConjunctions; ++family) {
    for (uint64_t seed = 1; seed <= 20; ++seed) {
      test::RandomSceneMaker maker(1000 * (family + 1) + seed);
      const auto r =
          maker.conjunctive_scene(static_cast<test::RandomSceneMaker::Conjunction>(family));
      c.run(r.scene, radiating_faces(r.scene, seed), r.sites,
            "family " + std::to_string(family) + " seed " + std::to_string(seed));
    }
  }
  EXPECT_EQ(c.failures, 0) << "of " << c.points << " points";
  EXPECT_GT(c.culled, 0);
}

TEST(VisibleSet, PassesOverWhatClosedWallsHide) {
  // Two rooms with no door: from inside the first, nothing of the second (its furniture
  // included) is kept; with the doors of rooms_with_doors, the second room's polygons seen
  // through the door are.
  test::SceneBuilder b;
  const int white = b.material("white", Rgb::Constant(0.5), Rgb::Zero());
  b.box({0, 0, 0}, {1, 1, 1}, white);
  const int first_of_second = static_cast<int>(b.scene().polygons.size());
  b.box({1.5, 0, 0}, {2.5, 1, 1}, white);
  for (int i = 0; i < 10; ++i)
    b.box({1.6 + 0.08 * i, 0.1, 0.2}, {1.65 + 0.08 * i, 0.3, 0.4}, white);
  const Scene& scene = b.scene();
  std::vector<std::vector<EmittingFace>> pieces(scene.polygons.size());
  for (EmittingFace& f : faces_from_polygons(scene)) pieces[f.polygon].push_back(std::move(f));
  const VisibleSet set(scene, pieces);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  std::normal_distribution<double> g;
  for (int i = 0; i < 50; ++i) {
    const std::vector<int> kept =
        set.polygons(Vec3(u(rng), u(rng), u(rng)), Vec3(g(rng), g(rng), g(rng)).normalized());
    ASSERT_FALSE(kept.empty());
    EXPECT_LT(kept.back(), first_of_second) << "a polygon behind closed walls was kept";
  }
  // Through the door: from the first room's floor, looking up, the second room's walls show.
  const Scene with_doors = rooms_with_doors(2, 3, 1);
  std::vector<std::vector<EmittingFace>> door_pieces(with_doors.polygons.size());
  for (EmittingFace& f : faces_from_polygons(with_doors))
    door_pieces[f.polygon].push_back(std::move(f));
  const VisibleSet doors(with_doors, door_pieces);
  const std::vector<int> kept = doors.polygons(Vec3(0.5, 0, 0.5), Vec3::UnitY());
  // The long walls, floor and ceiling run through both rooms; the far end wall (index 5) shows
  // through the door.
  EXPECT_TRUE(std::ranges::binary_search(kept, 5));
}

}  // namespace
}  // namespace rad
