#include "geometry/lambert.h"

#include <array>

#include "geometry/clip.h"

namespace rad {

double point_polygon_form_factor(const Vec3& x, const Vec3& n, const std::vector<Vec3>& polygon) {
  // Clipping keeps a polygon wholly above the horizon as it is (vertices on the horizon too), so
  // the usual small polygon skips the clip and the heap; the values are the same bit for bit.
  constexpr size_t kStack = 16;
  if (polygon.size() <= kStack) {
    std::array<Vec3, kStack> relative;
    bool above = true;
    for (size_t i = 0; i < polygon.size() && above; ++i) {
      relative[i] = polygon[i] - x;
      above = n.dot(polygon[i] - x) >= 0;
    }
    if (above) {
      if (polygon.size() < 3) return 0;
      return std::abs(lambert_loop(std::span<const Vec3>(relative.data(), polygon.size()), n));
    }
  }
  std::vector<Vec3> visible = clip_to_halfspace(polygon, x, n);
  if (visible.size() < 3) return 0;
  for (Vec3& v : visible) v -= x;
  return std::abs(lambert_loop(visible, n));
}

}  // namespace rad
