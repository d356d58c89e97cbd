#pragma once
/// Which patches a shot can reach at all, found without visiting the others: a patch emits from
/// its front only (DESIGN §3), so nothing at or behind its plane receives from it; and a point
/// receives only from in front of its own tangent plane, which for an element is its patch's
/// plane. Either way the form factor is exactly zero (to the scene's in-plane tolerance), so
/// leaving such receivers out of a shot changes nothing they hold. A finely tessellated floor
/// is the case that needs it: its triangles are coplanar, each of its patches shoots, and each
/// shot used to ask every element of the floor for a form factor of zero.
#include <array>
#include <vector>

#include "geometry/box_tree.h"
#include "radiosity/solution.h"

namespace rad {

class ReceiverCulling {
 public:
  /// `receives_at_back[p]`: patch p takes light at its back too (a filter's patches: the ledger
  /// asks them), so only the shooter's plane culls it. `enabled` false (a scene with mirrors:
  /// a receiver behind the shooter's plane sees its images) culls nothing. `in_plane`: the
  /// scene's tolerance (Tolerance::in_plane).
  ReceiverCulling(const std::vector<Patch>& patches, std::vector<char> receives_at_back,
                  double in_plane, bool enabled);

  /// The patches that may receive from `shooter`, in index order (the shooter's own polygon
  /// included no more than any other coplanar patch: never). One call at a time: it marks
  /// patches in a scratch of its own.
  void receivers(int shooter, std::vector<int>& out) const;

  /// Whether patch `receiver` may receive from patch `shooter`: the pairwise rule that
  /// receivers() applies to every patch it does not skip by whole boxes.
  bool may_receive(int receiver, int shooter) const;

 private:
  /// The height of the farthest point of `box` above the plane of `shooter`.
  double highest_above(const Eigen::AlignedBox3d& box, int shooter) const;

  /// What may_receive() reads of a patch, in one place: the test runs for half the building's
  /// patches at every shot, and a Patch keeps its corners behind a pointer of their own.
  struct Plate {
    std::array<Vec3, 4> corners;  ///< The first `count` are the patch's
    Vec3 normal;
    int count = 0;
  };

  const std::vector<Patch>& patches_;
  std::vector<Plate> plates_;  ///< Per patch
  std::vector<char> receives_at_back_;
  double in_plane_;
  bool enabled_;
  BoxTree<3> tree_;
  mutable std::vector<int> candidates_;  ///< receivers()'s scratch: the patches its boxes take...
  mutable std::vector<char> marked_;     ///< ...and, per patch, whether it receives
};

}  // namespace rad
