#pragma once
/// Module `octree` (rad_octree): the energy-bounded octree over the patches of a solution
/// (paper 004 §4.1-4.2; DESIGN.md §3 eqs. 5-9): leaves of roughly equal energy, Bmax per voxel,
/// and the view-dependent bounds Bound(x, v) that order the local pass.
///
/// May use: geometry.
#include <Eigen/Geometry>
#include <vector>

#include "geometry/vec.h"

namespace rad {

/// What the octree stores: a convex planar piece radiating `radiosity` from its front.
struct OctreeItem {
  std::vector<Vec3> corners;  ///< Counter-clockwise about `normal`.
  Vec3 normal = Vec3::UnitZ();
  Rgb radiosity = Rgb::Zero();
};

/// The leaf test (eq. 6). A voxel's energy proxy is max_c Bmax_c(v) * diagonal(v)^2, with the
/// diagonal of the box around its items: the power it can radiate is at most Bmax times its
/// items' area, and that area grows like the diagonal squared. A voxel stays a leaf when
///   proxy(v) <= energy_fraction * proxy(root) * 2^level,   or it holds <= min_items items,
///   or level == max_level.
/// The first part aims at equal energy per leaf (eq. 6's left side); the factor 2^level relaxes
/// it with depth, so that a small bright patch (the lamp) does not drive the tree to max_level:
/// halving a voxel divides its proxy by ~4, so the depth reached grows like log_8 of the inverse
/// fraction instead of log_4. The default 2^-21 gives ~7 levels where radiosity is uniform:
/// about 2000 leaves of ~4 elements for the demo's 8500 elements. Measured on that solution
/// with the eq. 8 ordering, before shaft culling (32x32 pixels, tolerance 0.2): 52 leaves
/// (fraction 2^-9) gathered 61% of the elements per pixel, 389 leaves (2^-15) 32%, 2025 leaves
/// 8%: small voxels let the bound select finely.
struct OctreeSettings {
  double energy_fraction = 1.0 / (1 << 21);
  int min_items = 4;
  int max_level = 8;
};

struct Voxel {
  Eigen::AlignedBox3d cell;    ///< The octree cell (its children halve it).
  Eigen::AlignedBox3d bounds;  ///< Box around the items it holds (all its descendants' items).
  int level = 0;
  int first_child = -1;    ///< Children first_child .. first_child + 7 (empty ones too); -1: leaf.
  std::vector<int> items;  ///< Leaves only: indices into the item list.
  int item_count = 0;      ///< Items in this voxel and below.
  Rgb bmax = Rgb::Zero();  ///< Eq. 5: the largest radiosity of any item in it, per channel.

  bool is_leaf() const { return first_child < 0; }
};

/// The octree. Items are not split at voxel faces: each goes to the child whose cell holds its
/// centroid, and a voxel's bounds grow to hold its items whole (a loose octree). Bounds then
/// overlap a little between siblings, which costs nothing in correctness (every bound below is
/// taken over the voxel's own items) and keeps the items the solver's elements, unsplit.
class Octree {
 public:
  Octree(std::vector<OctreeItem> items, const OctreeSettings& settings = {});

  const std::vector<OctreeItem>& items() const { return items_; }
  const std::vector<Voxel>& voxels() const { return voxels_; }  ///< voxels()[0] is the root.
  const std::vector<int>& leaves() const { return leaves_; }    ///< Non-empty leaves.
  /// Items of voxel v and its descendants.
  std::vector<int> items_below(int v) const;

  /// The most voxels an octree of `items` items can have, for an estimate of its memory before
  /// it is built. Below max_level, the inner voxels of one level hold disjoint sets of more
  /// than min_items items, so a level has at most min(8^level, items / (min_items + 1)) of them;
  /// each has 8 children, and the root is one more.
  static long long max_voxels(long long items, const OctreeSettings& settings = {});

  /// Eq. 7: Bmax(v) * FF(x, silhouette of v's bounds), FF = 1 when x is inside them.
  Rgb bound_eq7(int v, const Vec3& x, const Vec3& n) const;
  /// Eq. 8: as eq. 7 with the maximum taken only over items that can send light to x (x on
  /// their front side and some corner above x's tangent plane). Leaves scan their items;
  /// inner voxels take the largest of their children's eq. 8 maxima. Both bound the visible
  /// contribution of the voxel's items from above: whatever of them is visible lies inside the
  /// silhouette of their box, and radiates at most their largest radiosity.
  Rgb bound(int v, const Vec3& x, const Vec3& n) const;
  /// Eq. 8's maximum alone: the largest radiosity, per channel, of v's items that can light x.
  Rgb bmax_toward(int v, const Vec3& x, const Vec3& n) const;

 private:
  void build(int v, std::vector<int> items, const OctreeSettings& settings, double root_proxy);

  std::vector<OctreeItem> items_;
  std::vector<Voxel> voxels_;
  std::vector<int> leaves_;
};

/// The form factor of an axis-aligned box's silhouette for a receiver at x with unit normal n
/// (what lies above x's tangent plane): the sum over the faces x sees from outside, which tile
/// the silhouette without overlap. 1 when x is inside or on the box.
double box_form_factor(const Eigen::AlignedBox3d& box, const Vec3& x, const Vec3& n);

}  // namespace rad
