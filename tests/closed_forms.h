#pragma once
/// Closed forms for tests: configuration factors (Howell's catalog; docs/
/// formfactors.md) and Fresnel's reflectances. Independent of the code under test: plain
/// formulas.
#include <cmath>
#include <numbers>

namespace rad::test {

/// Howell B-3: element at the origin with normal +z, rectangle z = c, x in [0, a], y in [0, b].
inline double howell_b3(double a, double b, double c) {
  const double X = a / c, Y = b / c;
  return (X / std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) +
          Y / std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y))) /
         (2 * std::numbers::pi);
}

/// The rectangle [x0, x1] x [y0, y1] at height c above the origin (normal +z), by signed
/// superposition of B-3 corner rectangles.
inline double howell_rectangle(double x0, double x1, double y0, double y1, double c) {
  auto corner = [&](double x, double y) {
    return (x < 0 ? -1 : 1) * (y < 0 ? -1 : 1) * howell_b3(std::abs(x), std::abs(y), c);
  };
  return corner(x1, y1) - corner(x0, y1) - corner(x1, y0) + corner(x0, y0);
}

/// Fresnel's reflectances of s and p light at an interface of relative index eta (far / near)
/// for light arriving at angle i from the normal, in Hecht's sine and tangent forms (not the
/// cosine forms geometry/refraction.h uses); the limit ((eta - 1) / (eta + 1))^2 at normal
/// incidence. Requires sin(i) < eta (short of total internal reflection).
struct FresnelReflectance {
  double s, p;
  double unpolarised() const { return 0.5 * (s + p); }
};
inline FresnelReflectance hecht_reflectance(double i, double eta) {
  if (i < 1e-9) {
    const double r = std::pow((eta - 1) / (eta + 1), 2);
    return {r, r};
  }
  const double t = std::asin(std::sin(i) / eta);
  return {std::pow(std::sin(i - t) / std::sin(i + t), 2),
          std::pow(std::tan(i - t) / std::tan(i + t), 2)};
}

/// Test vectors from docs/formfactors.md (15 digits).
struct HowellCase {
  double a, b, c;  ///< B-3: (a, b, c); perpendicular: (w, h, s)
  double F;
};
/// B-3: element at the origin with normal +z, rectangle z = c, x in [0, a], y in [0, b].
inline constexpr HowellCase kHowellB3[] = {{1, 1, 1, 0.138531605994893},
                                           {2, 3, 1, 0.217575206107758},
                                           {0.5, 4, 2, 0.058114170266747},
                                           {10, 10, 1, 0.247971408295310},
                                           {1, 2, 5, 0.022519707332294}};
/// Perpendicular: element at the origin with normal +z, rectangle in the plane y = s,
/// x in [0, w], z in [0, h].
inline constexpr HowellCase kHowellPerpendicular[] = {{1, 1, 1, 0.055734197002554},
                                                      {2, 3, 1, 0.147825402362980},
                                                      {3, 1, 2, 0.023989639422154},
                                                      {0.5, 4, 2, 0.031064728833287},
                                                      {10, 10, 1, 0.221738670869958}};

}  // namespace rad::test
