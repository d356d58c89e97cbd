#pragma once
/// Closed-form configuration factors for tests (Howell's catalog; shared/ground-truth/
/// formfactors.md). Independent of the code under test: plain formulas.
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

}  // namespace rad::test
