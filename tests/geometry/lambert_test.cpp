#include "geometry/lambert.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "geometry/clip.h"
#include "geometry/plane.h"
#include "scene/polygon.h"
#include "tests/closed_forms.h"

namespace rad {
namespace {

constexpr double kPi = std::numbers::pi;

using test::howell_b3;

TEST(FormFactor, MatchesHowellB3ParallelRectangleThroughCorner) {
  for (const auto& c : test::kHowellB3) {
    const std::vector<Vec3> rect{{0, 0, c.c}, {c.a, 0, c.c}, {c.a, c.b, c.c}, {0, c.b, c.c}};
    const double ff = point_polygon_form_factor(Vec3::Zero(), Vec3::UnitZ(), rect);
    EXPECT_NEAR(ff, c.F, 1e-12 * c.F) << "a=" << c.a << " b=" << c.b << " c=" << c.c;
    EXPECT_NEAR(ff, howell_b3(c.a, c.b, c.c), 1e-12 * c.F);
  }
}

TEST(FormFactor, OffsetRectangleBySignedSuperpositionOfCorners) {
  // Rectangle [x0, x1] x [y0, y1] at height c = four corner rectangles with signs.
  const double x0 = 0.3, x1 = 1.7, y0 = -0.4, y1 = 0.9, c = 0.8;
  auto corner = [&](double x, double y) {
    return std::copysign(1.0, x) * std::copysign(1.0, y) * howell_b3(std::abs(x), std::abs(y), c);
  };
  const double expected = corner(x1, y1) - corner(x0, y1) - corner(x1, y0) + corner(x0, y0);
  const std::vector<Vec3> rect{{x0, y0, c}, {x1, y0, c}, {x1, y1, c}, {x0, y1, c}};
  EXPECT_NEAR(point_polygon_form_factor(Vec3::Zero(), Vec3::UnitZ(), rect), expected,
              1e-12 * expected);
}

TEST(FormFactor, MatchesHowellPerpendicularRectangle) {
  // Element at the origin, normal +z; rectangle in the plane y = s, x in [0, w], z in [0, h].
  for (const auto& c : test::kHowellPerpendicular) {
    const double w = c.a, h = c.b, s = c.c;
    const std::vector<Vec3> rect{{0, s, 0}, {w, s, 0}, {w, s, h}, {0, s, h}};
    EXPECT_NEAR(point_polygon_form_factor(Vec3::Zero(), Vec3::UnitZ(), rect), c.F, 1e-12 * c.F)
        << "w=" << w << " h=" << h << " s=" << s;
  }
}

TEST(FormFactor, MatchesDiskOnAxisInTheLimitOfManySides) {
  // B-12: F = 1 / (1 + (h/r)^2) for a disk; a regular n-gon inscribed in it falls short by a
  // known amount, which vanishes as n grows: compare against the n-gon of the same area.
  for (double h : {0.5, 1.0, 2.0}) {
    const int n = 4096;
    // Circumradius giving the n-gon the disk's area (r = 1): (n/2) R^2 sin(2 pi / n) = pi.
    const double R = std::sqrt(2 * kPi / (n * std::sin(2 * kPi / n)));
    std::vector<Vec3> ngon;
    for (int i = 0; i < n; ++i)
      ngon.emplace_back(R * std::cos(2 * kPi * i / n), R * std::sin(2 * kPi * i / n), h);
    const double disk = 1 / (1 + h * h);
    EXPECT_NEAR(point_polygon_form_factor(Vec3::Zero(), Vec3::UnitZ(), ngon), disk, 1e-6 * disk)
        << "h=" << h;
  }
}

TEST(FormFactor, OrientationAndOneSidednessHelpers) {
  const std::vector<Vec3> ccw{{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  std::vector<Vec3> cw(ccw.rbegin(), ccw.rend());
  const double a = point_polygon_form_factor(Vec3::Zero(), Vec3::UnitZ(), ccw);
  EXPECT_EQ(a, point_polygon_form_factor(Vec3::Zero(), Vec3::UnitZ(), cw));
  // The quad's front (counter-clockwise about +z) faces away from the origin.
  EXPECT_FALSE(is_in_front_of(Vec3::Zero(), ccw[0], Vec3::UnitZ()));
  EXPECT_TRUE(is_in_front_of(Vec3::Zero(), ccw[0], -Vec3::UnitZ()));
  // Entirely below the horizon, and in the receiver's plane: 0.
  EXPECT_EQ(point_polygon_form_factor(Vec3::Zero(), -Vec3::UnitZ(), ccw), 0.0);
  const std::vector<Vec3> flat{{1, 0, 0}, {2, 0, 0}, {2, 1, 0}};
  EXPECT_EQ(point_polygon_form_factor(Vec3::Zero(), Vec3::UnitZ(), flat), 0.0);
}

TEST(FormFactor, ClipsPolygonsCrossingTheTangentPlane) {
  // A vertical square straddling the tangent plane: only its upper half counts, and the upper
  // half alone is Howell's perpendicular case.
  const std::vector<Vec3> straddling{{0, 1, -1}, {1, 1, -1}, {1, 1, 1}, {0, 1, 1}};
  EXPECT_NEAR(point_polygon_form_factor(Vec3::Zero(), Vec3::UnitZ(), straddling), 0.055734197002554,
              1e-12);
  const auto clipped = clip_to_halfspace(straddling, Vec3::Zero(), Vec3::UnitZ());
  ASSERT_EQ(clipped.size(), 4u);
  for (const Vec3& p : clipped) EXPECT_GE(p.z(), 0.0);
}

/// Seeded Monte Carlo estimate: cosine-weighted directions from x, counting those that hit the
/// polygon (plane hit + 2D point-in-polygon). Independent of the contour formula.
double monte_carlo_form_factor(const Vec3& x, const Vec3& n, const std::vector<Vec3>& polygon,
                               int samples, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const PlaneFrame local(x, n);
  const Vec3 pn = newell_vector(polygon).normalized();
  const PlaneFrame plane(polygon[0], pn);
  std::vector<Vec2> flat;
  for (const Vec3& p : polygon) flat.push_back(plane.to_2d(p));
  int hits = 0;
  for (int i = 0; i < samples; ++i) {
    const double r = std::sqrt(u(rng)), phi = 2 * kPi * u(rng);
    const Vec3 d =
        r * std::cos(phi) * local.u + r * std::sin(phi) * local.v + std::sqrt(1 - r * r) * n;
    const double denom = pn.dot(d);
    if (denom == 0) continue;
    const double t = pn.dot(polygon[0] - x) / denom;
    if (t > 0 && contains_2d(flat, plane.to_2d(x + t * d))) ++hits;
  }
  return static_cast<double>(hits) / samples;
}

TEST(FormFactor, AgreesWithMonteCarloOnConcaveAndStraddlingPolygons) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 6; ++trial) {
    // A random concave star polygon in a random plane near the receiver; often it crosses
    // the receiver's tangent plane.
    const Vec3 centre(u(rng), u(rng), 0.2 + std::abs(u(rng)));
    const Vec3 normal = Vec3(g(rng), g(rng), g(rng)).normalized();
    const PlaneFrame f(centre, normal);
    std::vector<Vec3> star;
    for (int k = 0; k < 10; ++k) {
      const double radius = (k % 2 ? 0.35 : 1.0) * (0.6 + 0.4 * std::abs(u(rng)));
      star.push_back(
          centre + radius * (std::cos(2 * kPi * k / 10) * f.u + std::sin(2 * kPi * k / 10) * f.v));
    }
    const double exact = point_polygon_form_factor(Vec3::Zero(), Vec3::UnitZ(), star);
    const int samples = 1000000;
    const double mc =
        monte_carlo_form_factor(Vec3::Zero(), Vec3::UnitZ(), star, samples, 1000 + trial);
    const double sigma = std::sqrt(std::max(mc * (1 - mc), 1e-12) / samples);
    EXPECT_NEAR(exact, mc, 4 * sigma + 1e-12)
        << "trial " << trial << ": exact " << exact << " mc " << mc;
  }
}

TEST(FormFactor, SumsToOneInsideAClosedBox) {
  // Every point inside a closed box sees its walls with form factors summing to 1.
  const std::vector<std::vector<Vec3>> box{
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 0, 2}, {1, 0, 2}, {1, 1, 2}, {0, 1, 2}},
      {{0, 0, 0}, {1, 0, 0}, {1, 0, 2}, {0, 0, 2}}, {{0, 1, 0}, {1, 1, 0}, {1, 1, 2}, {0, 1, 2}},
      {{0, 0, 0}, {0, 1, 0}, {0, 1, 2}, {0, 0, 2}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 2}, {1, 0, 2}}};
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.01, 0.99);
  std::normal_distribution<double> g;
  for (int i = 0; i < 200; ++i) {
    const Vec3 x(u(rng), u(rng), 2 * u(rng));
    const Vec3 n = Vec3(g(rng), g(rng), g(rng)).normalized();
    double sum = 0;
    for (const auto& wall : box) sum += point_polygon_form_factor(x, n, wall);
    ASSERT_NEAR(sum, 1.0, 1e-12) << "x=" << x.transpose() << " n=" << n.transpose();
  }
}

}  // namespace
}  // namespace rad
