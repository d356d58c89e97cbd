#pragma once
/// The visible-surface structure seen from a point x (paper 004 §3; DESIGN.md §4): a 2D BSP of
/// great-circle planes through x whose leaves are convex spherical cells, each either empty or
/// showing one polygon. It is the shadow-volume BSP tree of Chin and Feiner (1989) with x as the
/// light, extended to resolve depth inside a cell, so polygons may come in any order and may
/// interpenetrate:
///  - a fragment reaching an empty cell is carved out of it by its own edge planes;
///  - a fragment reaching a cell that shows polygon Q is split by the plane through x on which
///    both are equally deep, m = c_F n_Q - c_Q n_F (so that each part is entirely in front of or
///    behind Q: this is where interpenetrating polygons are split by each other's plane), and
///    each part nearer than Q along a ray through it is carved into the cell.
/// Coplanar overlapping polygons are equally deep everywhere; the lower id shows. Everything is
/// a sign of a dot product with a plane normal; nothing is sampled.
#include <vector>

#include "hemisphere/spherical_polygon.h"

namespace rad::hemi {

/// A planar convex polygon seen from x = origin.
struct Occluder {
  int id = -1;        ///< Caller's identifier (e.g. scene polygon index).
  Vec3 normal;        ///< Unit normal of its plane.
  double offset = 0;  ///< normal . p for any point p of the plane (relative to x); != 0.
  /// Depth along unit direction d: the distance from x to the plane (positive in its cone).
  double depth(const Vec3& d) const { return offset / normal.dot(d); }
};

/// One visible piece: a convex spherical cell and the polygon it shows.
struct Fragment {
  int id;
  SphericalPolygon region;
};

class VisibleSurface {
 public:
  VisibleSurface();

  /// Inserts the part `region` (convex, inside the receiver's upper hemisphere) of polygon
  /// `occluder`. Insertion order does not change which polygon shows where; inserting front to
  /// back is fastest (far polygons then stop at the first depth test). Cost: the BSP's depth per
  /// fragment piece.
  void insert(const Occluder& occluder, const SphericalPolygon& region);

  /// The form factor (receiver normal n) of the part of `region` of polygon `occluder` that
  /// would show if it were inserted, without inserting it: the same walk and depth tests as
  /// insert, summing the pieces that would be carved instead of carving them. In a cell that
  /// shows a polygon in the same plane, it shows when its id is lower or the same (a polygon
  /// does not hide itself).
  double visible_form_factor(const Occluder& occluder, const SphericalPolygon& region,
                             const Vec3& n) const;

  /// The visible fragments (cells that show a polygon), in a deterministic order.
  std::vector<Fragment> fragments() const;
  /// The occluder record of an inserted id.
  const Occluder& occluder(int index) const { return occluders_[index]; }

  /// Sum of the fragments' form factors for a receiver with unit normal n: the cosine-weighted
  /// covered fraction of the hemisphere ("Covered" of paper 004 eq. 10).
  double covered_form_factor(const Vec3& n) const;

 private:
  struct Node {
    Vec3 plane = Vec3::Zero();  ///< Internal nodes: unit normal of a plane through x.
    int positive = -1;          ///< Child on the plane . d >= 0 side (inside the carving edge).
    int negative = -1;
    int occupant = -1;        ///< Leaves: index into occluders_, or -1 when empty.
    SphericalPolygon region;  ///< Occupied leaves: the cell.
    bool leaf() const { return positive < 0; }
  };

  void insert_at(int node, int occupant, const SphericalPolygon& piece);
  double visible_at(int node, const Occluder& occluder, const SphericalPolygon& piece,
                    const Vec3& n) const;
  /// Replaces leaf `node` by a subtree that carves `piece` (inside the leaf's cell) out of it:
  /// the piece's cell shows `occupant`, the rest keeps what the leaf showed.
  void carve(int node, int occupant, const SphericalPolygon& piece);

  std::vector<Node> nodes_;
  std::vector<Occluder> occluders_;
};

}  // namespace rad::hemi
