#pragma once
/// Lambert's contour formula (DESIGN.md §3; e.g. Baum et al. 1989), written once: the form
/// factor from a differential receiver at x with unit normal n to a polygon it sees whole,
///   FF = (1 / 2 pi) |sum over edges (v_i, v_i+1) of angle(v_i, v_i+1) n . unit(v_i x v_i+1)|,
/// with v_i relative to x. Every exact result of the project ends in it: the unoccluded faces
/// of the local pass, the visible spherical polygons of the hemisphere method (004 §3), the
/// solver's form factors and the octree's bounds.
///
/// The per-edge term is a free function of plain arrays so that a batched (SIMD) version can
/// replace the loops without touching the callers.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include "geometry/vec.h"

namespace rad {

/// One edge's term: angle(a, b) n . unit(a x b), a and b relative to x. The angle is
/// atan2(|a x b|, a . b): accurate for tiny and for nearly opposite arcs alike (DESIGN.md §7).
/// A zero-length edge, or one through x, contributes 0.
inline double lambert_edge(const Vec3& a, const Vec3& b, const Vec3& n) {
  const Vec3 c = a.cross(b);
  const double c_norm = c.norm();
  if (!(c_norm > 0)) return 0;
  return std::atan2(c_norm, a.dot(b)) * n.dot(c) / c_norm;
}

/// The same term when the unit normal k of the edge's plane through x is known exactly (a
/// spherical polygon keeps its edge planes through splits: hemisphere/spherical_polygon.h).
inline double lambert_edge(const Vec3& a, const Vec3& b, const Vec3& n, const Vec3& k) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * n.dot(k);
}

/// Signed contribution of one closed loop (vertices relative to x, in n's upper half-space):
/// (1 / 2 pi) sum_i lambert_edge(v_i, v_i+1, n). Loops of opposite orientation have opposite
/// signs, so a polygon with holes is its outer loop plus its holes listed the other way round,
/// and FF = |sum over loops|.
inline double lambert_loop(std::span<const Vec3> loop, const Vec3& n) {
  double sum = 0;
  for (size_t i = 0; i < loop.size(); ++i)
    sum += lambert_edge(loop[i], loop[(i + 1) % loop.size()], n);
  return sum / (2 * std::numbers::pi);
}

/// Unoccluded form factor from a differential receiver at x with unit normal n to a planar
/// polygon (absolute coordinates): Lambert's formula after clipping the polygon to x's upper
/// half-space (geometry/clip.h). The polygon's orientation does not matter (the result is
/// >= 0); one-sidedness is the caller's business (geometry/plane.h). Degenerate edges
/// contribute 0. Exact to rounding for any simple polygon, convex or not; x on the polygon's
/// plane gives 0. Cost O(#V).
double point_polygon_form_factor(const Vec3& x, const Vec3& n, const std::vector<Vec3>& polygon);

/// An upper bound on the form factor from a differential receiver to any surface of `area`
/// no part of which is closer than `gap`: cos cos / (pi r^2) <= 1 / (pi gap^2) over it, and no
/// form factor exceeds 1 (gap <= 0: the surface may touch the receiver).
inline double form_factor_bound(double area, double gap) {
  return gap > 0 ? std::min(1.0, area / (std::numbers::pi * gap * gap)) : 1.0;
}

}  // namespace rad
