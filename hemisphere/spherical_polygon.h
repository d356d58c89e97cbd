#pragma once
/// Convex spherical polygons around a point x (x at the origin): the projection of a planar
/// convex polygon onto the unit sphere (paper 004 §3; DESIGN.md §4). Every edge is the arc cut
/// by a plane through x; side tests are one dot product with that plane's normal.
#include <boost/container/small_vector.hpp>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/vec.h"

namespace rad::hemi {

/// Unit directions of a spherical polygon, held inline up to 8 (a clipped quad rarely has
/// more): the visible-surface walk splits polygons at every node, and a heap allocation per
/// split was a fifth of the local pass's time.
using Directions = boost::container::small_vector<Vec3, 8>;

/// A convex spherical polygon: unit vertices in order, every edge a minor arc, the whole inside
/// an open hemisphere. Each edge also stores the unit normal of its plane through x, pointing
/// into the polygon. Normals are never recomputed from vertices after construction: a split
/// keeps the parent's normals for the surviving parts of its edges and adds the cutting plane's,
/// so edge planes stay exact even when a split puts two vertices within rounding of each other
/// (a plane through two nearly equal directions would be numerically arbitrary). Empty when it
/// has fewer than 3 vertices or (numerically) no area.
class SphericalPolygon {
 public:
  SphericalPolygon() = default;
  /// From direction vectors (any length > 0, relative to x), reordered to the canonical
  /// orientation; near-duplicate consecutive directions are merged.
  explicit SphericalPolygon(const std::vector<Vec3>& directions);

  const Directions& vertices() const { return vertices_; }
  bool empty() const { return vertices_.size() < 3; }

  /// The parts on the positive (m . d >= 0) and negative side of the plane through x with unit
  /// normal m (Sutherland-Hodgman on the sphere; crossings are normalized chord points, which
  /// lie exactly on both planes up to rounding). Vertices within 1e-15 of the plane count as on
  /// it, so no sliver vertices are made. Either part may be empty.
  std::pair<SphericalPolygon, SphericalPolygon> split(const Vec3& m) const;

  /// True when direction d (any length) is inside or on the boundary: one dot product per edge
  /// with its plane normal (tolerance 1e-15 after normalizing d).
  bool contains(const Vec3& d) const;

  /// +1 when the polygon lies on the positive side of the plane through x with unit normal m
  /// (touching allowed), -1 on the negative side, 0 when the plane cuts it. Same tolerance as
  /// split(); allocates nothing.
  int side_of(const Vec3& m) const;

  /// The unit normal of edge i's plane (the edge from vertex i to i+1), pointing inside.
  const Vec3& edge_normal(size_t i) const { return normals_[i]; }
  /// A direction strictly inside (the normalized vertex mean).
  Vec3 interior_direction() const;

  /// Lambert's contour formula (geometry/lambert.h) with the stored edge planes: the form
  /// factor for a receiver with unit normal n at x, (1 / 2 pi) |sum_i angle(v_i, v_i+1) n .
  /// normal_i|. Assumes the polygon lies in the receiver's upper hemisphere (n . v >= 0 for all
  /// vertices).
  double form_factor(const Vec3& n) const;

 private:
  /// Takes vertices with their outgoing edges' normals as built by split(); merges
  /// coincident vertices (keeping the later outgoing normal) and empties degenerate results.
  SphericalPolygon(const Directions& vertices, const Directions& normals);

  Directions vertices_;
  Directions normals_;  ///< normals_[i]: plane of the edge vertices_[i] -> vertices_[i+1]
};

/// Where the minor arcs a0-a1 and b0-b1 (unit vectors, each arc shorter than pi) cross: the
/// normalized cross product of their planes' normals, taking the one of its two antipodes that
/// lies within both arcs. Nothing when the arcs do not cross, touch only at an endpoint, or lie
/// on one great circle (the caller then compares endpoints).
std::optional<Vec3> arc_intersection(const Vec3& a0, const Vec3& a1, const Vec3& b0,
                                     const Vec3& b1);

/// Boolean operations on convex spherical polygons, with the same exact splits the visible-
/// surface structure uses. Results are sets of convex pieces, which also represent concave
/// results and results with holes (their form factors add). A concave polygon enters as its
/// convex pieces (e.g. the triangles of its planar triangulation), operation by operation.
/// a intersect b: zero or one piece.
std::vector<SphericalPolygon> intersect(const SphericalPolygon& a, const SphericalPolygon& b);
/// a minus b: up to one piece per edge of b (each the part of a outside that edge and inside
/// the edges before it). Shared edges and vertices produce no slivers: points within 1e-15 of a
/// plane count as on it.
std::vector<SphericalPolygon> subtract(const SphericalPolygon& a, const SphericalPolygon& b);

/// Form factor of a spherical polygon with holes: |lambert_loop(outer) + sum lambert_loop(hole)|
/// (geometry/lambert.h) where every hole runs opposite to the outer loop.
double form_factor_with_holes(const std::vector<Vec3>& outer,
                              const std::vector<std::vector<Vec3>>& holes, const Vec3& n);

}  // namespace rad::hemi
