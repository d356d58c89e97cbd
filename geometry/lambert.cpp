#include "geometry/lambert.h"

#include "geometry/clip.h"

namespace rad {

double point_polygon_form_factor(const Vec3& x, const Vec3& n, const std::vector<Vec3>& polygon) {
  std::vector<Vec3> visible = clip_to_halfspace(polygon, x, n);
  if (visible.size() < 3) return 0;
  for (Vec3& v : visible) v -= x;
  return std::abs(lambert_loop(visible, n));
}

}  // namespace rad
