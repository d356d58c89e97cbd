#pragma once
/// The scene's polygon: its vertices and normal, and where it came from. Its planar predicates
/// (area, projection, self-intersection, triangulation, containment) are geometry/planar.h.
///
/// Convention (DESIGN.md §3): vertices are listed counter-clockwise seen from the front; the
/// front normal follows the right-hand rule. Surfaces are one-sided (only the front emits and
/// reflects) and opaque from both sides.
#include <vector>

#include "geometry/planar.h"
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

/// The shading normal at point x of polygon p (on its plane): its vertex normals (a smooth
/// mesh's) interpolated over the triangle of p that holds x, barycentrically (the triangles of
/// triangulate(), as the glossy beams split it), normalised; p.normal without vertex normals.
Vec3 shading_normal(const Polygon& p, const Vec3& x);

/// Point-in-polygon test by winding number in 2D; points on the boundary count as inside.
bool contains_2d(const std::vector<Vec2>& polygon, const Vec2& p);

}  // namespace rad
