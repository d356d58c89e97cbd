#include "vertex/vertex_formula.h"

#include <cmath>
#include <numbers>

#include "geometry/clip.h"
#include "scene/polygon.h"

namespace rad {

double stark_F_slope_term(double x, double y, double m) {
  const double b = y - m * x;  // the edge's intercept
  const double C = 1 / std::sqrt(1 + m * m + b * b);
  return 0.5 * C * b * std::atan(C * (x + m * y));
}

double stark_F(double x, double y, double m) {
  const double A = 1 / std::sqrt(1 + x * x);
  return 0.5 * A * x * std::atan(A * y) + stark_F_slope_term(x, y, m);
}

double stark_vertex_term(double x, double y, double m_in, bool in_vertical, double m_out,
                         bool out_vertical) {
  if (!in_vertical && !out_vertical)
    return stark_F_slope_term(x, y, m_in) - stark_F_slope_term(x, y, m_out);
  const double in = in_vertical ? 0.0 : stark_F(x, y, m_in);
  const double out = out_vertical ? 0.0 : stark_F(x, y, m_out);
  return in - out;
}

double stark_G(double x, double y, const Vec3& k) {
  return -0.5 * k.z() * std::atan(k.y() * x - k.x() * y);
}

double stark_form_factor(const Vec3& x, const Vec3& n, const std::vector<Vec3>& polygon) {
  // Horizon clip at a small height h above x's tangent plane, in 3D (the same clip the
  // radiosity solver's Lambert formula uses, moved up by h), then the local frame: u, v span
  // the tangent plane, n is "up".
  double size = 0;
  for (const Vec3& p : polygon) size = std::max(size, (p - x).norm());
  const double h = kStarkHorizon * size;
  const PlaneFrame frame(Vec3::Zero(), n);
  std::vector<Vec3> clipped;
  for (const Vec3& p : clip_to_halfspace(polygon, x + h * n, n)) {
    const Vec3 d = p - x;
    clipped.emplace_back(frame.u.dot(d), frame.v.dot(d), std::max(n.dot(d), h));
  }
  const size_t count = clipped.size();
  if (count < 3) return 0;
  // Each edge's plane through x, from its 3D endpoints: exact lines even where the projected
  // endpoints are far away. A zero-length edge has no plane and contributes nothing.
  std::vector<Vec3> k(count);
  for (size_t i = 0; i < count; ++i) {
    const Vec3 cross = clipped[i].cross(clipped[(i + 1) % count]);
    const double norm = cross.norm();
    k[i] = norm > 0 ? Vec3(cross / norm) : Vec3::Zero();
  }
  double sum = 0;
  for (size_t i = 0; i < count; ++i) {
    const double px = clipped[i].x() / clipped[i].z(), py = clipped[i].y() / clipped[i].z();
    sum += stark_G(px, py, k[(i + count - 1) % count]) - stark_G(px, py, k[i]);
  }
  return std::abs(sum) / std::numbers::pi;
}

}  // namespace rad
