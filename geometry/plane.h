#pragma once
/// Which side of a polygon's plane a point lies on: the facing tests every gatherer and the
/// culling share (DESIGN.md §3: surfaces are one-sided, only the front emits and reflects).
#include "geometry/vec.h"

namespace rad {

/// Signed distance of the plane with unit normal `normal` through `plane_point`, seen from x:
/// normal . (plane_point - x). Negative when x lies in front of the plane.
inline double plane_offset_from(const Vec3& x, const Vec3& plane_point, const Vec3& normal) {
  return normal.dot(plane_point - x);
}

/// True when x lies strictly in front of the plane with unit normal `normal` through
/// `plane_point`: only then can the front of a polygon in that plane send light to x.
inline bool is_in_front_of(const Vec3& x, const Vec3& plane_point, const Vec3& normal) {
  return normal.dot(x - plane_point) > 0;
}

}  // namespace rad
