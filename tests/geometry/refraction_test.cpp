#include "geometry/refraction.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "tests/closed_forms.h"

namespace rad {
namespace {

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

TEST(Refraction, SnellsLawSinesAndPlane) {
  // 000 eq. 6 read off the result: n_near sin(near) = n_far sin(far), the refracted ray in the
  // plane of incidence, on the far side; for either orientation of the normal.
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> index(0.6, 2.4);
  int refracted = 0, reflected = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 n = random_unit(rng), d = random_unit(rng);
    const double eta = index(rng);
    const double sin_near = n.cross(d).norm();
    const auto t = refract(d, n, eta);
    if (sin_near > eta) {
      EXPECT_FALSE(t) << "beyond the critical angle: eta " << eta << " sin " << sin_near;
      ++reflected;
      continue;
    }
    ASSERT_TRUE(t) << "eta " << eta << " sin " << sin_near;
    ++refracted;
    EXPECT_NEAR(t->norm(), 1, 1e-14);
    EXPECT_NEAR(eta * n.cross(*t).norm(), sin_near, 1e-12) << "eta " << eta;
    EXPECT_NEAR(n.cross(d).normalized().dot(*t), 0, 1e-12) << "out of the plane of incidence";
    EXPECT_GT(n.dot(d) * n.dot(*t), 0) << "not on the far side";
  }
  EXPECT_GT(refracted, 500);
  EXPECT_GT(reflected, 100);
  // Normal incidence goes straight on; index 1 changes nothing.
  EXPECT_NEAR((*refract(-Vec3::UnitZ(), Vec3::UnitZ(), 1.5) + Vec3::UnitZ()).norm(), 0, 1e-15);
  const Vec3 oblique = Vec3(1, 2, -3).normalized();
  EXPECT_NEAR((*refract(oblique, Vec3::UnitZ(), 1) - oblique).norm(), 0, 1e-15);
}

TEST(Refraction, ContractedPointsLieOnTheLineOfSight) {
  // Eqs. 7-9 against Snell's law: a point q on the refracted ray of the line of sight r -> c
  // (a depth t behind c) is moved by the contraction onto the straight continuation of that
  // line. Nothing of eqs. 7-9 is used to build q.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), index(0.5, 2.5), length(0.01, 10);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 n = random_unit(rng);
    const Vec3 c(u(rng), u(rng), u(rng));
    Vec3 r = c + length(rng) * random_unit(rng);
    if (std::abs((r - c).dot(n)) < 1e-3 * (r - c).norm()) continue;
    if ((r - c).dot(n) < 0) r = c - (r - c);  // the receiver in front, the normal toward it
    const double eta = index(rng);
    const Vec3 d = (c - r).normalized();
    const double cos_near = -d.dot(n);
    const auto k = depth_ratio(cos_near, eta);
    const auto t = refract(d, n, eta);
    ASSERT_EQ(k.has_value(), t.has_value()) << "TIR disagrees: eta " << eta << " cos " << cos_near;
    if (!k) continue;
    const Vec3 q = c + length(rng) * *t;
    const DepthContraction contraction{c, n, *k};
    const Vec3 moved = contraction(q);
    // On the line r + s d, at depth k times q's.
    const Vec3 off_line = (moved - r) - (moved - r).dot(d) * d;
    EXPECT_LT(off_line.norm(), 1e-11 * (1 + (q - r).norm()))
        << "eta " << eta << " cos " << cos_near << " k " << *k;
    EXPECT_NEAR((c - moved).dot(n), *k * (c - q).dot(n), 1e-12 * (1 + (c - q).norm()));
    // The affine form is the same map.
    EXPECT_LT((contraction.linear() * q + contraction.translation() - moved).norm(),
              1e-12 * (1 + q.norm()));
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

TEST(Refraction, DepthRatioLimits) {
  // Index 1: nothing moves. Normal incidence: the paraxial apparent depth 1 / n. The critical
  // angle exactly (cos^2 = 1 - eta^2): total internal reflection, and just inside it k -> oo.
  EXPECT_EQ(*depth_ratio(0.3, 1.0), 1.0);
  EXPECT_NEAR(*depth_ratio(1.0, 1.5), 1 / 1.5, 1e-15);
  EXPECT_NEAR(*depth_ratio(1.0, 1 / 1.5), 1.5, 1e-15);
  const double eta = 1 / 1.5, cos_critical = std::sqrt(1 - eta * eta);
  EXPECT_FALSE(depth_ratio(cos_critical * (1 - 1e-12), eta));
  EXPECT_FALSE(depth_ratio(0.0, eta));
  EXPECT_GT(*depth_ratio(cos_critical * (1 + 1e-9), eta), 1e3);
  // Edge-on into a denser medium: everything seen collapses onto the plane.
  EXPECT_EQ(*depth_ratio(0.0, 1.5), 0.0);
}

TEST(Refraction, FresnelAgainstTheSineAndTangentForms) {
  // Hecht's forms (independent of the cosine forms the code uses): R_s = sin^2(i - t) /
  // sin^2(i + t), R_p = tan^2(i - t) / tan^2(i + t); normal incidence ((n - 1)/(n + 1))^2;
  // Brewster's angle passes all p light; the reversed path passes the same (Stokes).
  for (const double eta : {1.2, 1.5, 2.4, 1 / 1.33, 1 / 1.5}) {
    EXPECT_NEAR(fresnel_transmission(1.0, eta), 1 - std::pow((eta - 1) / (eta + 1), 2), 1e-15);
    for (double i = 0.01; i < 1.56; i += 0.01) {
      const double sin_t = std::sin(i) / eta;
      if (sin_t >= 1) {
        EXPECT_EQ(fresnel_transmission(std::cos(i), eta), 0.0) << "TIR at " << i;
        continue;
      }
      const double t = std::asin(sin_t);
      const double expected = 1 - test::hecht_reflectance(i, eta).unpolarised();
      EXPECT_NEAR(fresnel_transmission(std::cos(i), eta), expected, 1e-12)
          << "eta " << eta << " angle " << i;
      EXPECT_NEAR(fresnel_transmission(std::cos(t), 1 / eta), expected, 1e-12)
          << "reversed: eta " << eta << " angle " << i;
    }
    const double brewster = std::atan(eta);
    const test::FresnelReflectance at_brewster = test::hecht_reflectance(brewster, eta);
    EXPECT_NEAR(at_brewster.p, 0, 1e-15);
    EXPECT_NEAR(fresnel_transmission(std::cos(brewster), eta), 1 - 0.5 * at_brewster.s, 1e-12);
  }
  EXPECT_NEAR(fresnel_transmission(1e-9, 1.5), 0, 1e-8) << "grazing light is all reflected";
  EXPECT_EQ(fresnel_transmission(0.7, 1.0), 1.0);
}

}  // namespace
}  // namespace rad
