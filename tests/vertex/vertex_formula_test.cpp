// Stark's vertex formula (paper 001 eqs. 6-8) against Howell's closed forms and against
// Lambert's contour formula (geometry/lambert.h), an independent computation.
#include "vertex/vertex_formula.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <random>

#include "geometry/lambert.h"
#include "scene/polygon.h"
#include "tests/closed_forms.h"

namespace rad {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(StarkFormula, MatchesHowellRectangles) {
  for (const auto& c : test::kHowellB3) {
    const std::vector<Vec3> rect{{0, 0, c.c}, {c.a, 0, c.c}, {c.a, c.b, c.c}, {0, c.b, c.c}};
    EXPECT_NEAR(stark_form_factor(Vec3::Zero(), Vec3::UnitZ(), rect), c.F, 1e-12 * c.F);
  }
  for (const auto& c : test::kHowellPerpendicular) {
    // The bottom edge lies in the tangent plane: the horizon clip is exercised.
    const std::vector<Vec3> rect{{0, c.c, 0}, {c.a, c.c, 0}, {c.a, c.c, c.b}, {0, c.c, c.b}};
    EXPECT_NEAR(stark_form_factor(Vec3::Zero(), Vec3::UnitZ(), rect), c.F, 1e-12 * c.F);
  }
  const double expected = test::howell_rectangle(-0.7, 1.3, 0.2, 2.9, 1.5);
  const std::vector<Vec3> offset{
      {-0.7, 0.2, 1.5}, {1.3, 0.2, 1.5}, {1.3, 2.9, 1.5}, {-0.7, 2.9, 1.5}};
  EXPECT_NEAR(stark_form_factor(Vec3::Zero(), Vec3::UnitZ(), offset), expected, 1e-12 * expected);
}

TEST(StarkFormula, AgreesWithLambertOnRandomPolygons) {
  std::mt19937_64 rng(1001);
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> g;
  double worst = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    // Random convex or star-shaped (concave) polygons in random planes around random points,
    // many crossing the receiver's tangent plane.
    const Vec3 centre(2 * u(rng), 2 * u(rng), 1.5 * u(rng) + 0.3);
    const Vec3 normal = Vec3(g(rng), g(rng), g(rng)).normalized();
    const PlaneFrame f(centre, normal);
    const int k = 3 + trial % 8;
    const bool star = trial % 3 == 0 && k >= 6;
    std::vector<Vec3> polygon;
    for (int i = 0; i < k; ++i) {
      const double r = (star && i % 2) ? 0.3 : 0.5 + 0.5 * std::abs(u(rng)) * !star + 0.5 * star;
      polygon.push_back(centre +
                        r * (std::cos(2 * kPi * i / k) * f.u + std::sin(2 * kPi * i / k) * f.v));
    }
    const Vec3 n = Vec3(0.3 * g(rng), 0.3 * g(rng), 1).normalized();
    const double lambert = point_polygon_form_factor(Vec3::Zero(), n, polygon);
    const double stark = stark_form_factor(Vec3::Zero(), n, polygon);
    const double error = std::abs(stark - lambert);
    // 1e-12 relative, with an absolute floor of 1e-13 (rounding in either formula).
    worst = std::max(worst, error / std::max(lambert, 0.1));
    ASSERT_LE(error, 1e-12 * std::max(lambert, 0.1))
        << "trial " << trial << ": stark " << stark << " lambert " << lambert;
  }
  std::cout << "worst difference to Lambert over 5000 random polygons: " << worst
            << " (relative above 0.1)\n";
}

TEST(StarkFormula, VerticalAndNearlyVerticalEdges) {
  // A rectangle whose projected edges are exactly vertical (x constant), then rotated by tiny
  // angles: the value is continuous through the omitted-term case.
  const std::vector<Vec3> square{{0.2, -0.5, 1}, {1.2, -0.5, 1}, {1.2, 0.7, 1}, {0.2, 0.7, 1}};
  const double exact = test::howell_rectangle(0.2, 1.2, -0.5, 0.7, 1);
  EXPECT_NEAR(stark_form_factor(Vec3::Zero(), Vec3::UnitZ(), square), exact, 1e-13);
  for (double angle : {1e-15, 1e-12, 1e-9, 1e-6}) {
    std::vector<Vec3> turned;
    const Vec3 c(0.7, 0.1, 1);
    for (const Vec3& p : square) {
      const Vec3 d = p - c;
      turned.push_back(c + Vec3(std::cos(angle) * d.x() - std::sin(angle) * d.y(),
                                std::sin(angle) * d.x() + std::cos(angle) * d.y(), 0));
    }
    EXPECT_NEAR(stark_form_factor(Vec3::Zero(), Vec3::UnitZ(), turned),
                point_polygon_form_factor(Vec3::Zero(), Vec3::UnitZ(), turned), 1e-13)
        << "angle " << angle;
  }
}

TEST(StarkFormula, PlaneNormalFormEqualsThePapersSlopeForm) {
  // stark_G with the edge plane's normal equals the m-dependent term of F (eq. 7) for any
  // line, either orientation of the normal, and at a vertical edge equals minus F's first term.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-5, 5);
  for (int i = 0; i < 10000; ++i) {
    const double x = u(rng), y = u(rng), m = u(rng), b = y - m * x;
    const Vec3 k = Vec3(m, -1, b).normalized();  // the line Y = m X + b through the vertex
    ASSERT_NEAR(stark_G(x, y, k), stark_F_slope_term(x, y, m), 1e-15);
    ASSERT_NEAR(stark_G(x, y, -k), stark_F_slope_term(x, y, m), 1e-15);
    // The paper's vertex term (slopes, vertical edges omitted) against the plane-normal form.
    const double m2 = u(rng), b2 = y - m2 * x;
    const Vec3 k_in = Vec3(m, -1, y - m * x).normalized(), k_out = Vec3(m2, -1, b2).normalized();
    ASSERT_NEAR(stark_vertex_term(x, y, m, false, m2, false),
                stark_G(x, y, k_in) - stark_G(x, y, k_out), 1e-14);
    const Vec3 vertical = Vec3(1, 0, -x).normalized();  // the line X = x
    ASSERT_NEAR(stark_vertex_term(x, y, m, false, 0, true),
                stark_G(x, y, k_in) - stark_G(x, y, vertical), 1e-14);
  }
}

TEST(StarkFormula, ExtraneousCollinearVertexContributesNothing) {
  const std::vector<Vec3> plain{{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
  const std::vector<Vec3> with_t{{-1, -1, 1}, {0.3, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
  EXPECT_NEAR(stark_form_factor(Vec3::Zero(), Vec3::UnitZ(), with_t),
              stark_form_factor(Vec3::Zero(), Vec3::UnitZ(), plain), 1e-15);
  // Per vertex: equal incoming and outgoing slopes cancel exactly.
  EXPECT_EQ(stark_vertex_term(0.3, -1, 0.25, false, 0.25, false), 0.0);
}

TEST(StarkFormula, TinyAndFarPolygonsWithMeasuredError) {
  // Tiny: squares down to 1e-9 of their distance, 30 degrees off axis, against Lambert's
  // contour formula (atan2 form, accurate at any size; DESIGN.md §7).
  const double off = std::tan(kPi / 6);
  for (double s : {1e-3, 1e-6, 1e-9}) {
    const std::vector<Vec3> tiny{{off - s / 2, -s / 2, 1},
                                 {off + s / 2, -s / 2, 1},
                                 {off + s / 2, s / 2, 1},
                                 {off - s / 2, s / 2, 1}};
    const double reference = point_polygon_form_factor(Vec3::Zero(), Vec3::UnitZ(), tiny);
    const double error =
        std::abs(stark_form_factor(Vec3::Zero(), Vec3::UnitZ(), tiny) - reference) / reference;
    std::cout << "square of size " << s << " at unit distance: relative difference to Lambert "
              << error << "\n";
    // Vertex terms of order s cancel to a result of order s^2: relative error ~1e-16 / s
    // (measured 4.7e-11 at 1e-6 and 4.6e-8 at 1e-9).
    EXPECT_LT(error, 1e-15 / s) << "size " << s;
  }
  // Large coordinates: a 1e5 square at 1e6, and the same seen from a far-away receiver.
  const std::vector<Vec3> far{{0, 0, 1e6}, {1e5, 0, 1e6}, {1e5, 1e5, 1e6}, {0, 1e5, 1e6}};
  EXPECT_NEAR(stark_form_factor(Vec3::Zero(), Vec3::UnitZ(), far), test::howell_b3(1e5, 1e5, 1e6),
              1e-12 * test::howell_b3(1e5, 1e5, 1e6));
  const Vec3 shift(3e7, -2e7, 5e6);
  std::vector<Vec3> shifted;
  for (const Vec3& p : far) shifted.push_back(p + shift);
  EXPECT_NEAR(stark_form_factor(shift, Vec3::UnitZ(), shifted), test::howell_b3(1e5, 1e5, 1e6),
              1e-9 * test::howell_b3(1e5, 1e5, 1e6));
}

}  // namespace
}  // namespace rad
