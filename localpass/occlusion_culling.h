#pragma once
/// Which faces can be hidden from a point, and by what (shaft culling, Haines and Wallace 1994).
/// Most of what a point sees in a room is seen whole: the walls
/// of a box never hide each other from inside it. Such faces need no visibility work at all:
/// their contribution is the unoccluded form factor of their part above the horizon (Lambert's
/// formula, exact). Only faces that something may hide go to an exact gatherer, together with
/// the faces that may hide them.
///
/// Why it is exact. A face g hides part of a face f from x only if some segment from x to a
/// point y of f passes through g. Then
///  - x is off g's plane (a plane through x subtends nothing; both gatherers skip such faces),
///  - g's plane separates x from y, so it separates x from the box around f, and
///  - g meets the shaft from x to f's box (the hull of x and the box; geometry/shaft.h),
/// and all three hold as well for g's polygon, for any convex outline holding f and any box
/// holding the outline. The local pass asks this of its clusters (blockers), from the polygons
/// that passed for the parent cluster down to the faces. A cluster no polygon passes for is
/// seen whole; for a face that may be hidden, its occluders are the faces of the passing
/// polygons that meet the shaft (found through the octree; vertex tracing's). Coplanar overlapping
/// polygons hide each other by index in both gatherers, so they are always each other's
/// occluders. Tolerances: 1e-12 of the scene diagonal for "in the plane" and "separates" (the
/// gatherers' own), 1e-9 of it as padding on the shafts (on the safe side).
#include <Eigen/Geometry>
#include <span>
#include <utility>
#include <vector>

#include "octree/octree.h"
#include "scene/polygon_faces.h"
#include "scene/scene.h"

namespace rad {

struct OcclusionSplit {
  /// Faces that can light x and may be hidden, with the polygons that may hide one of them
  /// (OcclusionCulling::occluders lists their faces).
  struct Group {
    std::vector<int> faces;
    std::vector<int> blockers;  ///< Polygon indices, sorted
    Eigen::AlignedBox3d box;    ///< Around the faces
  };
  std::vector<Group> shadowed;
};

class OcclusionCulling {
 public:
  /// `octree` holds one item per face, in the same order (octree_items).
  OcclusionCulling(const Scene& scene, const std::vector<EmittingFace>& faces,
                   const Octree& octree);

  /// Polygons that may hide anything from (x, n): x off their plane (by more than half the
  /// gatherers' tolerance, so that every face the gatherers project is kept), part above the
  /// horizon. Polygon indices, ascending.
  std::vector<int> candidates(const Vec3& x, const Vec3& n) const;
  /// The same among `polygons` (ascending): those x may see (localpass/visible_set.h).
  std::vector<int> candidates(const Vec3& x, const Vec3& n, std::span<const int> polygons) const;
  /// Polygons among `candidates` (ascending) that may hide part of the convex planar `outline`
  /// of polygon `polygon` (in its box `box`) from x, ascending, plus the polygons coplanar with
  /// it that overlap it (they hide each other by index). Empty: nothing hides any of it.
  void blockers(std::span<const int> candidates, const Vec3& x, const Eigen::AlignedBox3d& box,
                const std::vector<Vec3>& outline, int polygon, std::vector<int>* out) const;
  /// Whether some polygon may hide part of a cluster of polygon `polygon` from
  /// some point of `region`, as blockers() would name one from any point x of it: a polygon
  /// x is off (by half the tolerance), whose plane separates x from part of the box, that meets
  /// the shaft between the two boxes (Shaft's box-to-box form), or a coplanar polygon that
  /// overlaps `polygon`. False: every point of `region` sees all of the box's part of the
  /// polygon whole. Cost: one pass over the scene's polygons.
  /// The region is given twice: as the points within `margin` of the hull of `hull` (for the
  /// planes' tests) and as a box around them (for the shaft); the cluster as its `outline`'s
  /// vertices (the planes' tests, as filter() takes them) and the box around it.
  bool may_hide_between(std::span<const Vec3> hull, double margin,
                        const Eigen::AlignedBox3d& region, std::span<const Vec3> outline,
                        const Eigen::AlignedBox3d& box, int polygon) const;
  /// Whether x is strictly in front of the polygon's plane (the gatherers' test).
  bool in_front_of_polygon(int polygon, const Vec3& x) const {
    return height(polygon, x) > in_plane_;
  }
  /// x's signed height over the polygon's plane (in_front_of_polygon asks for more than the
  /// gatherers' in-plane tolerance).
  double height(int polygon, const Vec3& x) const {
    return polygons_[polygon].normal.dot(x) - polygons_[polygon].offset;
  }
  /// The same faces with no culling: every one that can light x shadowed, in one group, with
  /// every face its occluder (the baseline the culling is measured against).
  OcclusionSplit split_without_culling(const Vec3& x, const Vec3& n) const;
  /// Every face that may hide part of the group's faces from x: the faces of its blockers that
  /// meet the shaft to its box (found through the octree). Appended to `out`.
  void occluders(const Vec3& x, const OcclusionSplit::Group& group, std::vector<int>* out) const;

 private:
  struct PolygonData {
    Vec3 normal;
    double offset = 0;  ///< normal . p on its plane
    std::vector<Vec3> vertices;
    Eigen::AlignedBox3d box;
    std::vector<int> coplanar_overlapping;  ///< Polygons that hide it (or that it hides) by index
  };
  static std::pair<double, double> height_range(const PolygonData& polygon,
                                                std::span<const Vec3> points);
  /// Polygons among `candidates` that may hide part of `box` (of `face`, when given, inside
  /// it) from x.
  void filter(std::span<const int> candidates, const Vec3& x, const Eigen::AlignedBox3d& box,
              const std::vector<Vec3>* face, std::vector<int>* out) const;
  bool can_light(int face, const Vec3& x, const Vec3& n) const;
  bool is_candidate(int polygon, const Vec3& x, const Vec3& n) const;

  const std::vector<EmittingFace>& faces_;
  const Octree& octree_;
  std::vector<PolygonData> polygons_;
  std::vector<Eigen::AlignedBox3d> face_boxes_;
  double in_plane_ = 0, pad_ = 0;
};

}  // namespace rad
