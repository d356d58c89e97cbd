#include "hemisphere/spherical_polygon.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "geometry/clip.h"
#include "hemisphere/visible_surface.h"
#include "tests/closed_forms.h"

namespace rad::hemi {
namespace {

using test::howell_b3;

TEST(SphericalPolygon, LambertMatchesHowellForAProjectedRectangle) {
  const SphericalPolygon rect({{0, 0, 1}, {2, 0, 1}, {2, 3, 1}, {0, 3, 1}});
  EXPECT_NEAR(rect.form_factor(Vec3::UnitZ()), 0.217575206107758, 1e-13);
  // Orientation is canonical: the same polygon listed the other way round is identical.
  const SphericalPolygon reversed({{0, 3, 1}, {2, 3, 1}, {2, 0, 1}, {0, 0, 1}});
  EXPECT_EQ(rect.vertices().size(), reversed.vertices().size());
  EXPECT_NEAR(reversed.form_factor(Vec3::UnitZ()), 0.217575206107758, 1e-13);
  for (size_t i = 0; i < rect.vertices().size(); ++i) {
    EXPECT_GT(rect.edge_normal(i).dot(rect.interior_direction()), 0) << "edge normals point inside";
  }
}

TEST(SphericalPolygon, SplitPartsAddUpAndLieOnTheirSides) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  const SphericalPolygon rect({{-1, -1, 1}, {1.5, -1, 1}, {1.5, 2, 1}, {-1, 2, 1}});
  const double whole = rect.form_factor(Vec3::UnitZ());
  for (int i = 0; i < 1000; ++i) {
    const Vec3 m = Vec3(g(rng), g(rng), 0.3 * g(rng)).normalized();
    const auto [pos, neg] = rect.split(m);
    ASSERT_NEAR(pos.form_factor(Vec3::UnitZ()) + neg.form_factor(Vec3::UnitZ()), whole, 1e-14)
        << m.transpose();
    for (const Vec3& v : pos.vertices()) ASSERT_GE(m.dot(v), -1e-15);
    for (const Vec3& v : neg.vertices()) ASSERT_LE(m.dot(v), 1e-15);
  }
  // A plane through the diagonal's two vertices: both halves keep those vertices exactly.
  const auto [left, right] = rect.split(Vec3(-1, -1, 1).cross(Vec3(1.5, 2, 1)).normalized());
  EXPECT_EQ(left.vertices().size(), 3u);
  EXPECT_EQ(right.vertices().size(), 3u);
}

// A mesh's boundary seen from close by: an edge of several collinear vertices, each a few ulps
// off its line, cut by that line's plane (a neighbouring polygon's edge). The signs can then
// form a pattern no convex polygon has (on the plane, below, above, below: issue 36). Before the
// fix the part above became a sliver whose stored edge planes ran out and back with the same
// normal, and Lambert's formula gave it the form factor of half the polygon (0.104 of a 0.127
// cluster at a Cornell box pixel, where the local pass's certified bound then failed).
TEST(SphericalPolygon, SplitAlongANoisyChainOfCollinearVerticesAddsUp) {
  std::mt19937_64 rng(36);
  std::uniform_int_distribution<int> ulps(-4, 4);
  int cut_by_noise = 0;
  // Not perpendicular to the cutting plane: Lambert's terms along it count.
  const Vec3 receiver = Vec3(0.2, -0.4, 0.9).normalized();
  for (int trial = 0; trial < 4000; ++trial) {
    // The edge lies on the plane y = 0 through x (its chain at height 1, from x = -1 to 1); the
    // rest of the polygon at y > 0.
    std::vector<Vec3> directions{{-1, 0, 1}};
    for (const double t : {-0.6, -0.2, 0.3, 0.7}) directions.emplace_back(t, ulps(rng) * 1e-15, 1);
    directions.insert(directions.end(), {{1, 0, 1}, {0.8, 1, 1}, {-0.7, 1.2, 1}});
    const SphericalPolygon polygon(directions);
    ASSERT_FALSE(polygon.empty());
    const double whole = polygon.form_factor(receiver);
    // The cutting plane: y = 0 itself, either way round, or tilted by an ulp.
    const Vec3 m = Vec3(ulps(rng) * 1e-16, trial % 2 ? 1.0 : -1.0, ulps(rng) * 1e-16).normalized();
    // Cut by noise alone: vertices beyond split()'s 1e-15 on both sides.
    bool above_by_noise = false, below_by_noise = false;
    for (const Vec3& v : polygon.vertices()) {
      above_by_noise |= m.dot(v) > 1e-15;
      below_by_noise |= m.dot(v) < -1e-15;
    }
    cut_by_noise += above_by_noise && below_by_noise;
    const auto [pos, neg] = polygon.split(m);
    const double above = pos.form_factor(receiver), below = neg.form_factor(receiver);
    ASSERT_NEAR(above + below, whole, 1e-13) << "trial " << trial;
    // Everything but a sliver of noise lies on the polygon's side of the plane.
    ASSERT_LT(std::min(above, below), 1e-13) << "trial " << trial;
  }
  EXPECT_GT(cut_by_noise, 1000) << "the test must reach the case it is for";
}

TEST(SphericalPolygon, HolesSubtractWithTheirOrientation) {
  // A 4 x 4 square with a 1 x 1 hole, at height 1: FF = FF(outer) - FF(hole), and the hole
  // listed the other way round does exactly that.
  const std::vector<Vec3> outer{{-2, -2, 1}, {2, -2, 1}, {2, 2, 1}, {-2, 2, 1}};
  const std::vector<Vec3> hole{
      {0.5, 0.5, 1}, {0.5, 1.5, 1}, {1.5, 1.5, 1}, {1.5, 0.5, 1}};  // clockwise
  const double expected =
      4 * howell_b3(2, 2, 1) -
      (howell_b3(1.5, 1.5, 1) - 2 * howell_b3(1.5, 0.5, 1) + howell_b3(0.5, 0.5, 1));
  EXPECT_NEAR(form_factor_with_holes(outer, {hole}, Vec3::UnitZ()), expected, 1e-13);
}

TEST(SphericalPolygon, DegenerateInputIsEmpty) {
  EXPECT_TRUE(SphericalPolygon({{0, 0, 1}, {1, 0, 1}}).empty());
  EXPECT_TRUE(SphericalPolygon({{0, 0, 1}, {1, 0, 1}, {2, 0, 1}}).empty())
      << "collinear: on one great circle";
  EXPECT_TRUE(SphericalPolygon({{1, 0, 0}, {2, 0, 0}, {1, 1, 0}}).empty())
      << "edge-on from x: a plane through x";
  // Coincident vertices are merged, not fatal.
  const SphericalPolygon dup({{0, 0, 1}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {1, 1, 1}});
  EXPECT_EQ(dup.vertices().size(), 3u);
}

TEST(SphericalPolygon, ClipsAtTheTangentPlaneExactlyIn3D) {
  const auto clipped = clip_to_halfspace({{0, 1, -1}, {1, 1, -1}, {1, 1, 1}, {0, 1, 1}},
                                         Vec3::Zero(), Vec3::UnitZ());
  ASSERT_EQ(clipped.size(), 4u);
  EXPECT_EQ(clipped[0], Vec3(1, 1, 0));  // the first crossing, then the kept upper vertices
  EXPECT_EQ(clipped[3], Vec3(0, 1, 0));
}

TEST(SphericalPredicates, PointInPolygonAndArcIntersection) {
  const SphericalPolygon square({{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}});
  EXPECT_TRUE(square.contains({0, 0, 1}));
  EXPECT_TRUE(square.contains({1, 0.3, 1})) << "on an edge";
  EXPECT_TRUE(square.contains({1, 1, 1})) << "on a vertex";
  EXPECT_FALSE(square.contains({1.01, 0, 1}));
  EXPECT_FALSE(square.contains({0, 0, -1})) << "the antipode of an inside point";
  // Two arcs crossing at (0, 0, 1) seen from the origin.
  const auto hit = arc_intersection(Vec3(-1, 0, 1).normalized(), Vec3(1, 0, 1).normalized(),
                                    Vec3(0, -1, 1).normalized(), Vec3(0, 1, 1).normalized());
  ASSERT_TRUE(hit);
  EXPECT_NEAR((*hit - Vec3(0, 0, 1)).norm(), 0, 1e-15);
  // Disjoint arcs on crossing great circles, arcs touching at an endpoint, and arcs on one
  // great circle: no crossing point.
  EXPECT_FALSE(arc_intersection(Vec3(-1, 0, 1).normalized(), Vec3(-0.5, 0, 1).normalized(),
                                Vec3(0, -1, 1).normalized(), Vec3(0, 1, 1).normalized()));
  EXPECT_FALSE(arc_intersection(Vec3(0, 0, 1), Vec3(1, 0, 1).normalized(), Vec3(0, 0, 1),
                                Vec3(0, 1, 1).normalized()));
  EXPECT_FALSE(arc_intersection(Vec3(-1, 0, 1).normalized(), Vec3(0, 0, 1),
                                Vec3(0.2, 0, 1).normalized(), Vec3(1, 0, 1).normalized()));
  // Random crossings: the point lies on both great circles and inside the polygon they bound.
  std::mt19937_64 rng(4);
  std::normal_distribution<double> g;
  int crossings = 0;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 a0 = Vec3(g(rng), g(rng), 3).normalized(), a1 = Vec3(g(rng), g(rng), 3).normalized();
    const Vec3 b0 = Vec3(g(rng), g(rng), 3).normalized(), b1 = Vec3(g(rng), g(rng), 3).normalized();
    if (const auto p = arc_intersection(a0, a1, b0, b1)) {
      ASSERT_NEAR(a0.cross(a1).normalized().dot(*p), 0, 1e-15);
      ASSERT_NEAR(b0.cross(b1).normalized().dot(*p), 0, 1e-15);
      ASSERT_GT(p->z(), 0) << "the crossing, not its antipode";
      ++crossings;
    }
  }
  EXPECT_GT(crossings, 100) << "too few crossing pairs to test anything";
}

double total_ff(const std::vector<SphericalPolygon>& pieces, const Vec3& n) {
  double sum = 0;
  for (const auto& p : pieces) sum += p.form_factor(n);
  return sum;
}

TEST(SphericalBoolean, IntersectionAndDifferencePartitionThePolygon) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(-1, 1);
  auto random_convex = [&](int k) {
    // A random convex polygon on the plane z = 1: points on a circle, sorted by angle.
    const Vec3 c(0.5 * u(rng), 0.5 * u(rng), 1);
    std::vector<double> angles;
    for (int i = 0; i < k; ++i) angles.push_back(3.14159 * u(rng));
    std::sort(angles.begin(), angles.end());
    std::vector<Vec3> pts;
    const double r = 0.3 + 0.5 * std::abs(u(rng));
    for (double a : angles) pts.push_back(c + r * Vec3(std::cos(a), std::sin(a), 0));
    return SphericalPolygon(pts);
  };
  const Vec3 n = Vec3::UnitZ();
  for (int trial = 0; trial < 500; ++trial) {
    const SphericalPolygon a = random_convex(3 + trial % 6), b = random_convex(3 + trial % 5);
    if (a.empty() || b.empty()) continue;
    const double fa = a.form_factor(n), fb = b.form_factor(n);
    const double both = total_ff(intersect(a, b), n);
    ASSERT_NEAR(both + total_ff(subtract(a, b), n), fa, 1e-14) << "trial " << trial;
    ASSERT_NEAR(both + total_ff(subtract(b, a), n), fb, 1e-14) << "trial " << trial;
    ASSERT_NEAR(total_ff(intersect(b, a), n), both, 1e-14) << "trial " << trial;
  }
}

TEST(SphericalBoolean, SharedEdgesAndIdenticalPolygons) {
  const Vec3 n = Vec3::UnitZ();
  const SphericalPolygon left({{-1, 0, 1}, {0, 0, 1}, {0, 1, 1}, {-1, 1, 1}});
  const SphericalPolygon right({{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}});
  EXPECT_TRUE(intersect(left, right).empty()) << "touching along an edge: no overlap";
  EXPECT_NEAR(total_ff(subtract(left, right), n), left.form_factor(n), 1e-15);
  EXPECT_TRUE(subtract(left, left).empty()) << "nothing is left, not even slivers";
  EXPECT_NEAR(total_ff(intersect(left, left), n), left.form_factor(n), 1e-15);
  // Touching at one vertex only.
  const SphericalPolygon corner({{0, 1, 1}, {1, 1, 1}, {1, 2, 1}, {0, 2, 1}});
  EXPECT_TRUE(intersect(left, corner).empty());
}

TEST(VisibleSurface, NearerPolygonHidesFartherWhateverTheOrder) {
  // Source 2 x 2 at height 2, a 1 x 1 blocker at height 1: from the origin the blocker hides
  // the centre of the source.
  const SphericalPolygon source({{-1, -1, 2}, {1, -1, 2}, {1, 1, 2}, {-1, 1, 2}});
  const SphericalPolygon blocker({{-0.5, -0.5, 1}, {0.5, -0.5, 1}, {0.5, 0.5, 1}, {-0.5, 0.5, 1}});
  const Occluder s{0, Vec3::UnitZ(), 2}, b{1, Vec3::UnitZ(), 1};
  for (int order = 0; order < 2; ++order) {
    VisibleSurface v;
    if (order == 0) {
      v.insert(s, source);
      v.insert(b, blocker);
    } else {
      v.insert(b, blocker);
      v.insert(s, source);
    }
    double ff_source = 0;
    for (const auto& f : v.fragments())
      ff_source += f.id == 0 ? f.region.form_factor(Vec3::UnitZ()) : 0;
    // The blocker's shadow on the source plane is [-1, 1]^2: it hides all of the source.
    EXPECT_NEAR(ff_source, 0.0, 1e-15) << "order " << order;
    EXPECT_NEAR(v.covered_form_factor(Vec3::UnitZ()), 4 * howell_b3(1, 1, 2), 1e-14);
  }
}

TEST(VisibleSurface, InterpenetratingPolygonsAreSplitByEachOthersPlane) {
  // Two rectangles crossing along the line x = 0 at height 1: A tilts up with x, B down.
  // Seen from below, A is nearer for x < 0 and B for x > 0.
  const std::vector<Vec3> a{{-1, -1, 0.5}, {1, -1, 1.5}, {1, 1, 1.5}, {-1, 1, 0.5}};
  const std::vector<Vec3> b{{-1, -1, 1.5}, {1, -1, 0.5}, {1, 1, 0.5}, {-1, 1, 1.5}};
  auto occluder = [](int id, const std::vector<Vec3>& p) {
    const Vec3 n = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
    return Occluder{id, n, n.dot(p[0])};
  };
  VisibleSurface v;
  v.insert(occluder(0, a), SphericalPolygon(a));
  v.insert(occluder(1, b), SphericalPolygon(b));
  double ff[2] = {0, 0};
  for (const auto& f : v.fragments()) {
    ff[f.id] += f.region.form_factor(Vec3::UnitZ());
    // Every fragment lies on one side of x = 0: A's on the negative, B's on the positive.
    for (const Vec3& d : f.region.vertices()) EXPECT_LE((f.id == 0 ? 1 : -1) * d.x(), 1e-12);
  }
  EXPECT_NEAR(ff[0], ff[1], 1e-14) << "mirror symmetry";
}

}  // namespace
}  // namespace rad::hemi
