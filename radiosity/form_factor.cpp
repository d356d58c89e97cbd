#include "radiosity/form_factor.h"

#include <cmath>
#include <numbers>

namespace rad {

std::vector<Vec3> clip_to_halfspace(const std::vector<Vec3>& polygon, const Vec3& x, const Vec3& n) {
  std::vector<Vec3> out;
  const size_t count = polygon.size();
  out.reserve(count + 2);
  for (size_t i = 0; i < count; ++i) {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % count];
    const double da = n.dot(a - x), db = n.dot(b - x);
    if (da >= 0) out.push_back(a);
    // The edge crosses the plane strictly: add the crossing, computed from the endpoint on the
    // positive side so that the result lies exactly on the kept side's segment.
    if ((da > 0 && db < 0) || (da < 0 && db > 0)) {
      const double t = da / (da - db);
      out.push_back(a + t * (b - a));
    }
  }
  return out;
}

double point_polygon_form_factor(const Vec3& x, const Vec3& n, const std::vector<Vec3>& polygon) {
  const std::vector<Vec3> visible = clip_to_halfspace(polygon, x, n);
  const size_t count = visible.size();
  if (count < 3) return 0;
  double sum = 0;
  for (size_t i = 0; i < count; ++i) {
    const Vec3 a = visible[i] - x;
    const Vec3 b = visible[(i + 1) % count] - x;
    const Vec3 c = a.cross(b);
    const double c_norm = c.norm();
    if (!(c_norm > 0)) continue;  // zero-length edge, or edge through x: no contribution
    // atan2 of |a x b| and a . b: the accurate angle for any size (DESIGN.md §7).
    const double angle = std::atan2(c_norm, a.dot(b));
    sum += angle * n.dot(c) / c_norm;
  }
  return std::abs(sum) / (2 * std::numbers::pi);
}

}  // namespace rad
