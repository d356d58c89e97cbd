#pragma once
/// The planar kernel: every operation on a polygon in its plane, written once. Polygons in 3D
/// (Newell's vector, extent, planarity, the frame of their plane) and in 2D (cross product,
/// signed area, convex hull, self-intersection, triangulation, containment). Counter-clockwise
/// in a plane's frame is counter-clockwise about its normal (DESIGN.md §3).
#include <array>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/vec.h"

namespace rad {

/// The 2D cross product a.x b.y - a.y b.x: positive when b turns counter-clockwise from a.
inline double cross_2d(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// The barycentric weights (u, v, w) of p in the 2D triangle (a, b, c): p = u a + v b + w c,
/// u + v + w = 1 (all >= 0 inside). None when the triangle has no area.
inline std::optional<std::array<double, 3>> barycentric_2d(const Vec2& a, const Vec2& b,
                                                           const Vec2& c, const Vec2& p) {
  const Vec2 e1 = b - a, e2 = c - a, d = p - a;
  const double det = cross_2d(e1, e2);
  if (!(std::abs(det) > 0)) return std::nullopt;
  const double v = cross_2d(d, e2) / det, w = cross_2d(e1, d) / det;
  return std::array{1 - v - w, v, w};
}

/// Newell's vector: twice the vector area of a (possibly non-planar) polygon. Its direction is
/// the best-fit front normal, its length twice the projected area. Exact for planar polygons.
Vec3 newell_vector(const std::vector<Vec3>& vertices);

/// Diagonal of the axis-aligned bounding box: the length scale every relative tolerance uses.
double extent(const std::vector<Vec3>& vertices);

/// Largest distance of a vertex from the plane with unit normal `n` through the vertex centroid.
double plane_deviation(const std::vector<Vec3>& vertices, const Vec3& n);

/// An orthonormal frame (u, v, n) of a plane, used to map a planar polygon to 2D. (u, v, n) is
/// right-handed, so a polygon counter-clockwise about n stays counter-clockwise in (u, v).
struct PlaneFrame {
  Vec3 origin;
  Vec3 u, v, n;
  explicit PlaneFrame(const Vec3& origin, const Vec3& unit_normal);
  Vec2 to_2d(const Vec3& p) const { return {u.dot(p - origin), v.dot(p - origin)}; }
  /// The point of the plane at 2D coordinates p (the inverse of to_2d on the plane).
  Vec3 to_3d(const Vec2& p) const { return origin + p.x() * u + p.y() * v; }
  /// The direction about n lifted from the point (sqrt(r2), phi) of the unit disk (Malley's
  /// method): with r2 and phi / (2 pi) uniform in [0, 1), directions are cosine-weighted.
  Vec3 cosine_direction(double r2, double phi) const {
    const double r = std::sqrt(r2);
    return r * std::cos(phi) * u + r * std::sin(phi) * v + std::sqrt(std::max(0.0, 1 - r2)) * n;
  }
};

/// Projects the polygon onto its plane (normal `n`): #V 2D points, same order.
std::vector<Vec2> project_to_plane(const std::vector<Vec3>& vertices, const Vec3& n);

/// Twice the signed area of a 2D polygon (positive when counter-clockwise): the sum over its
/// edges (p, q) of cross_2d(p - about, q - about). Any `about` gives the area; rounding grows
/// with the distance from `about` to the polygon.
double signed_area_2d(const std::vector<Vec2>& polygon, const Vec2& about);
/// The same about its first vertex, where rounding is least (the edges at it add exact zeros).
inline double signed_area_2d(const std::vector<Vec2>& polygon) {
  return signed_area_2d(polygon, polygon.front());
}

/// True when no corner of the 2D polygon turns against its orientation (the sign of its area;
/// collinear corners allowed).
bool is_convex(const std::vector<Vec2>& polygon);

/// Indices into `points` of their convex hull, counter-clockwise from the lowest-x point,
/// without collinear or repeated points (Andrew's monotone chain). Only points strictly inside
/// a hull edge are dropped, so the hull holds every point. Fewer than three distinct points
/// come back as they are (distinct, sorted).
std::vector<int> convex_hull(const std::vector<Vec2>& points);

/// Finds two edges of a closed 2D polygon that intersect other than at the vertex shared by
/// neighbours: crossing or touching non-adjacent edges, or adjacent edges that fold back onto
/// each other. A vertex lying on the straight continuation of its edges is allowed (T-junction
/// vertex). Returns the indices (i, j) of edges (p_i, p_i+1) and (p_j, p_j+1), i < j.
/// `tolerance` is the distance below which points count as touching. Cost O(#V log #V + k), k
/// the pairs of edges whose boxes (grown by `tolerance`) meet: a box tree names the candidates
/// (a polygon of 100,000 vertices in well under a second; a spiral, whose outer edges' boxes
/// hold the inner ones, still costs more).
std::optional<std::pair<int, int>> find_self_intersection(const std::vector<Vec2>& polygon,
                                                          double tolerance);

/// Triangulates a simple 2D polygon (either orientation, convex or concave) by ear clipping.
/// Returns #V-2 index triples with the polygon's orientation. Degenerate ears (collinear
/// vertices) are clipped last, so the result always has #V-2 triangles. Cost O(#V^2).
std::vector<std::array<int, 3>> triangulate(const std::vector<Vec2>& polygon);

}  // namespace rad
