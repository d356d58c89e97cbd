#include "geometry/refraction.h"

#include <cmath>

namespace rad {

std::optional<Vec3> refract(const Vec3& d, const Vec3& normal, double eta) {
  // With the normal turned toward the near side, cos_near = -d . n >= 0; the far direction is
  // d / eta + (cos_near / eta - cos_far) n, cos_far^2 = 1 - (1 - cos_near^2) / eta^2.
  const Vec3 n = normal.dot(d) > 0 ? Vec3(-normal) : normal;
  const double cos_near = std::min(1.0, -n.dot(d));
  const double cos_far2 = 1 - (1 - cos_near * cos_near) / (eta * eta);
  if (cos_far2 < 0) return std::nullopt;
  const Vec3 t = d / eta + (cos_near / eta - std::sqrt(cos_far2)) * n;
  return t.normalized();
}

std::optional<double> depth_ratio(double cos_near, double eta) {
  // eta^2 - sin^2 = eta^2 - 1 + cos^2 (eq. 8's denominator).
  const double radicand = eta * eta - 1 + cos_near * cos_near;
  if (!(radicand > 0)) return std::nullopt;
  return cos_near / std::sqrt(radicand);
}

double fresnel_transmission(double cos_near, double eta) {
  const double cos_i = std::min(1.0, std::abs(cos_near));
  const double cos_t2 = 1 - (1 - cos_i * cos_i) / (eta * eta);
  if (!(cos_t2 > 0)) return 0;
  const double cos_t = std::sqrt(cos_t2);
  const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 1 - 0.5 * (rs * rs + rp * rp);
}

}  // namespace rad
