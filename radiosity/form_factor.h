#pragma once
/// Point-to-polygon form factors (DESIGN.md §3): the fraction of the radiation leaving a
/// Lambertian polygon that arrives at a differential receiver, or equivalently the irradiance at
/// the receiver per unit exitance of the polygon.
#include <vector>

#include "scene/types.h"

namespace rad {

/// Clips a planar polygon to the half-space n . (p - x) >= 0 (one Sutherland-Hodgman pass,
/// exact in 3D, before any projection). Vertices on the plane are kept. Returns the clipped
/// polygon (possibly empty; possibly with fewer than 3 vertices).
std::vector<Vec3> clip_to_halfspace(const std::vector<Vec3>& polygon, const Vec3& x, const Vec3& n);

/// Unoccluded form factor from a differential receiver at x with unit normal n to the polygon
/// (Lambert's contour formula, e.g. Baum et al. 1989):
///   FF = (1 / 2 pi) sum_i angle(v_i, v_i+1) n . unit(v_i x v_i+1),  v_i = p_i - x,
/// after clipping the polygon to x's upper half-space. The polygon's orientation does not matter
/// (the result is >= 0); one-sidedness is the caller's business (see emitter_faces). Degenerate
/// edges (zero length, or collinear with x) contribute 0. Exact to rounding for any simple
/// polygon, convex or not; x on the polygon's plane gives 0. Cost O(#V).
double point_polygon_form_factor(const Vec3& x, const Vec3& n, const std::vector<Vec3>& polygon);

/// True when the front of a polygon with unit normal `polygon_normal` through `polygon_point`
/// faces x (x strictly in front of its plane): only then can it send light to x.
inline bool emitter_faces(const Vec3& polygon_point, const Vec3& polygon_normal, const Vec3& x) {
  return polygon_normal.dot(x - polygon_point) > 0;
}

}  // namespace rad
