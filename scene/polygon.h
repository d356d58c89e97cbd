#pragma once
/// Planar polygons and the geometric predicates the loader and every gatherer rely on.
///
/// Convention (DESIGN.md §3): vertices are listed counter-clockwise seen from the front; the
/// front normal follows the right-hand rule. Surfaces are one-sided (only the front emits and
/// reflects) and opaque from both sides.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/vec.h"

namespace rad {

/// One planar, simple polygon of the scene with its provenance.
struct Polygon {
  std::vector<Vec3> vertices;  ///< #V >= 3, counter-clockwise seen from the front.
  Vec3 normal{0, 0, 1};        ///< Unit front normal (Newell's method).
  double area = 0;             ///< Area in scene units squared.
  int material = -1;           ///< Index into Scene::materials.
  int object = -1;             ///< Index of the object in the scene file ("objects[i]").
  int source_index = -1;       ///< Polygon index inside its object (inline list or mesh face).
  int triangle = -1;           ///< Triangle index when a non-planar source was split, else -1.
  /// Unit normals at the vertices, for a mesh object marked "smooth" (the mean of the faces'
  /// normals around each vertex, weighted by area; paper 003 warps glossy beams by them);
  /// empty otherwise (the polygon's normal everywhere).
  std::vector<Vec3> vertex_normals;
};

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
  /// The direction about n lifted from the point (sqrt(r2), phi) of the unit disk (Malley's
  /// method): with r2 and phi / (2 pi) uniform in [0, 1), directions are cosine-weighted.
  Vec3 cosine_direction(double r2, double phi) const {
    const double r = std::sqrt(r2);
    return r * std::cos(phi) * u + r * std::sin(phi) * v + std::sqrt(std::max(0.0, 1 - r2)) * n;
  }
};

/// Projects the polygon onto its plane (normal `n`): #V 2D points, same order.
std::vector<Vec2> project_to_plane(const std::vector<Vec3>& vertices, const Vec3& n);

/// Twice the signed area of a 2D polygon (positive when counter-clockwise).
double signed_area_2d(const std::vector<Vec2>& polygon);

/// Finds two edges of a closed 2D polygon that intersect other than at the vertex shared by
/// neighbours: crossing or touching non-adjacent edges, or adjacent edges that fold back onto
/// each other. A vertex lying on the straight continuation of its edges is allowed (T-junction
/// vertex). Returns the indices (i, j) of edges (p_i, p_i+1) and (p_j, p_j+1), i < j.
/// `tolerance` is the distance below which points count as touching. Cost O(#V^2).
std::optional<std::pair<int, int>> find_self_intersection(const std::vector<Vec2>& polygon,
                                                          double tolerance);

/// Triangulates a simple 2D polygon (either orientation, convex or concave) by ear clipping.
/// Returns #V-2 index triples with the polygon's orientation. Degenerate ears (collinear
/// vertices) are clipped last, so the result always has #V-2 triangles. Cost O(#V^2).
std::vector<std::array<int, 3>> triangulate(const std::vector<Vec2>& polygon);

/// The shading normal at point x of polygon p (on its plane): its vertex normals (a smooth
/// mesh's) interpolated over the triangle of p that holds x, barycentrically (the triangles of
/// triangulate(), as the glossy beams split it), normalised; p.normal without vertex normals.
Vec3 shading_normal(const Polygon& p, const Vec3& x);

/// Point-in-polygon test by winding number in 2D; points on the boundary count as inside.
bool contains_2d(const std::vector<Vec2>& polygon, const Vec2& p);

}  // namespace rad
