#include "scene/polygon.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>

namespace rad {
namespace {

std::vector<Vec2> regular_polygon(int n, double radius = 1) {
  std::vector<Vec2> p;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    p.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  return p;
}

/// A random star-shaped (generally concave) polygon around the origin: simple by construction.
std::vector<Vec2> random_star(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> radius(0.2, 1.0);
  std::vector<Vec2> p;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    const double r = radius(rng);
    p.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return p;
}

double triangulation_area(const std::vector<Vec2>& p, const std::vector<std::array<int, 3>>& tris,
                          double* min_signed) {
  double sum = 0;
  *min_signed = std::numeric_limits<double>::infinity();
  for (const auto& t : tris) {
    const double a = signed_area_2d({p[t[0]], p[t[1]], p[t[2]]});
    sum += a;
    *min_signed = std::min(*min_signed, a);
  }
  return sum;
}

TEST(Polygon, NewellVectorOfUnitSquareIsTwiceAreaAlongNormal) {
  const std::vector<Vec3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const Vec3 n = newell_vector(square);
  EXPECT_NEAR(n.z(), 2.0, 1e-15);
  EXPECT_NEAR(n.x(), 0.0, 1e-15);
  // Far from the origin: relative-to-first-vertex summation keeps full precision.
  std::vector<Vec3> far = square;
  for (Vec3& v : far) v += Vec3(1e8, -3e8, 7e7);
  EXPECT_NEAR(newell_vector(far).z(), 2.0, 1e-6) << "cancellation far from the origin";
}

TEST(Polygon, PlaneFrameIsRightHandedForAnyNormal) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 n = Vec3(g(rng), g(rng), g(rng)).normalized();
    const PlaneFrame f(Vec3::Zero(), n);
    ASSERT_NEAR(f.u.cross(f.v).dot(n), 1.0, 1e-12) << "n = " << n.transpose();
    ASSERT_NEAR(f.u.dot(n), 0.0, 1e-12);
  }
}

TEST(Polygon, TriangulatesConvexPolygonsCompletely) {
  for (int n : {3, 4, 5, 17, 1024}) {
    const auto p = regular_polygon(n);
    const auto tris = triangulate(p);
    ASSERT_EQ(tris.size(), static_cast<size_t>(n - 2)) << "n = " << n;
    double min_signed = 0;
    EXPECT_NEAR(triangulation_area(p, tris, &min_signed), signed_area_2d(p), 1e-12);
    EXPECT_GT(min_signed, 0) << "a triangle flipped, n = " << n;
  }
}

TEST(Polygon, TriangulatesRandomConcavePolygonsInBothOrientations) {
  std::mt19937_64 rng(2024);
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<Vec2> p = random_star(rng, 3 + trial % 40);
    if (trial % 2) std::reverse(p.begin(), p.end());  // clockwise input
    const auto tris = triangulate(p);
    ASSERT_EQ(tris.size(), p.size() - 2) << "trial " << trial;
    double min_signed = 0;
    const double sum = triangulation_area(p, tris, &min_signed);
    ASSERT_NEAR(sum, signed_area_2d(p), 1e-12 * std::abs(signed_area_2d(p)) + 1e-14)
        << "trial " << trial;
    // Every triangle has the polygon's orientation (none folds over).
    ASSERT_GE(min_signed * (signed_area_2d(p) > 0 ? 1 : -1), -1e-15) << "trial " << trial;
  }
}

TEST(Polygon, TriangulatesPolygonWithCollinearVertices) {
  // A square with extra vertices on its edges (T-junction vertices): all must be used.
  const std::vector<Vec2> p{{0, 0}, {0.5, 0}, {1, 0}, {1, 0.5}, {1, 1}, {0, 1}, {0, 0.5}};
  const auto tris = triangulate(p);
  ASSERT_EQ(tris.size(), 5u);
  double min_signed = 0;
  EXPECT_NEAR(triangulation_area(p, tris, &min_signed), 2.0, 1e-15);
  EXPECT_GE(min_signed, 0);
}

/// The first pair (i, j), i < j, of non-adjacent edges that come within `tolerance` (distance
/// of segments by their end points: an independent, quadratic reference; adjacent edges are
/// left to the fold-back cases of FindsSelfIntersections).
std::optional<std::pair<int, int>> first_meeting_pair(const std::vector<Vec2>& p, double tol) {
  const int n = static_cast<int>(p.size());
  const auto point_segment = [](const Vec2& x, const Vec2& a, const Vec2& b) {
    const Vec2 ab = b - a;
    const double t = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (a + t * ab - x).norm();
  };
  const auto side = [](const Vec2& a, const Vec2& b, const Vec2& x) {
    const double s = (b - a).x() * (x - a).y() - (b - a).y() * (x - a).x();
    return (s > 0) - (s < 0);
  };
  for (int i = 0; i < n; ++i) {
    for (int j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      const Vec2 &a = p[i], &b = p[(i + 1) % n], &c = p[j], &d = p[(j + 1) % n];
      const bool cross = side(a, b, c) * side(a, b, d) < 0 && side(c, d, a) * side(c, d, b) < 0;
      const double gap = std::min({point_segment(a, c, d), point_segment(b, c, d),
                                   point_segment(c, a, b), point_segment(d, a, b)});
      if (cross || gap <= tol) return std::pair{i, j};
    }
  }
  return std::nullopt;
}

TEST(Polygon, SelfIntersectionByTheTreeIsTheFirstPairOfAPlainScan) {
  // Seeded random walks (many crossings), jittered circles (few or none) and circles with one
  // vertex pulled across: the pair found is the plain scan's first, wherever it lies.
  std::mt19937_64 rng(39);
  std::uniform_real_distribution<double> u(-1, 1);
  int found = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 4 + trial % 60;
    std::vector<Vec2> p;
    if (trial % 3 == 0) {
      for (int i = 0; i < n; ++i) p.emplace_back(u(rng), u(rng));
    } else {
      p = regular_polygon(n);
      for (Vec2& v : p) v *= 1 + 0.02 * u(rng);
      if (trial % 3 == 2) p[trial % n] = Vec2(u(rng), u(rng)) * 1.5;
    }
    const double tol = 1e-9;
    const auto tree = find_self_intersection(p, tol);
    const auto plain = first_meeting_pair(p, tol);
    // The tree also reports neighbours folding back; the plain scan does not look at them.
    if (tree && (tree->second == tree->first + 1 || (tree->first == 0 && tree->second == n - 1)))
      continue;
    ASSERT_EQ(tree.has_value(), plain.has_value()) << "trial " << trial;
    if (plain) {
      EXPECT_EQ(*tree, *plain) << "trial " << trial;
    }
    found += plain.has_value();
  }
  EXPECT_GT(found, 50);  // the trials do cross
  // 100,000 vertices, simple: the tree's query cost, not the square (the plain scan took 60 s).
  EXPECT_FALSE(find_self_intersection(regular_polygon(100000), 1e-9));
}

TEST(Polygon, FindsSelfIntersections) {
  const double tol = 1e-12;
  EXPECT_FALSE(find_self_intersection(regular_polygon(6), tol));
  // Bow tie: edges 0 and 2 cross.
  EXPECT_TRUE(find_self_intersection({{0, 0}, {1, 1}, {1, 0}, {0, 1}}, tol));
  // Pentagram (non-zero area, so the zero-area check cannot catch it).
  std::vector<Vec2> star;
  for (int i = 0; i < 5; ++i) {
    const double a = 2 * std::numbers::pi * (2 * i) / 5;
    star.emplace_back(std::cos(a), std::sin(a));
  }
  EXPECT_TRUE(find_self_intersection(star, tol));
  // A vertex touching a non-adjacent edge.
  EXPECT_TRUE(find_self_intersection({{0, 0}, {2, 0}, {2, 2}, {1, 0}, {0, 2}}, tol));
  // A spike folding back along its own edge.
  EXPECT_TRUE(find_self_intersection({{0, 0}, {2, 0}, {1, 0}, {1, 1}}, tol));
  // A vertex on the straight continuation of its edges is fine.
  EXPECT_FALSE(find_self_intersection({{0, 0}, {1, 0}, {2, 0}, {2, 1}, {0, 1}}, tol));
  // Concave but simple.
  EXPECT_FALSE(find_self_intersection({{0, 0}, {2, 0}, {2, 2}, {1, 0.5}, {0, 2}}, tol));
}

TEST(Polygon, ContainsCountsBoundaryAsInside) {
  const std::vector<Vec2> l_shape{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  EXPECT_TRUE(contains_2d(l_shape, {0.5, 1.5}));
  EXPECT_FALSE(contains_2d(l_shape, {1.5, 1.5}));  // in the notch
  EXPECT_TRUE(contains_2d(l_shape, {1, 0}));       // on an edge
  EXPECT_TRUE(contains_2d(l_shape, {2, 1}));       // on a vertex
  EXPECT_FALSE(contains_2d(l_shape, {3, 0.5}));
}

TEST(Polygon, PlaneDeviationMeasuresNonPlanarity) {
  // A saddle: by symmetry the best-fit normal is z and every corner is h off the plane z = 0.
  const double h = 0.03;
  const std::vector<Vec3> saddle{{0, 0, h}, {1, 0, -h}, {1, 1, h}, {0, 1, -h}};
  const Vec3 n = newell_vector(saddle).normalized();
  EXPECT_NEAR(n.z(), 1.0, 1e-15);
  EXPECT_NEAR(plane_deviation(saddle, n), h, 1e-15);
  const std::vector<Vec3> flat{{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  EXPECT_EQ(plane_deviation(flat, newell_vector(flat).normalized()), 0.0);
}

}  // namespace
}  // namespace rad
