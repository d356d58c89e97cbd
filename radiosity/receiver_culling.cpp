#include "radiosity/receiver_culling.h"

#include <algorithm>
#include <utility>

namespace rad {
namespace {

std::vector<Eigen::AlignedBox3d> patch_boxes(const std::vector<Patch>& patches) {
  std::vector<Eigen::AlignedBox3d> boxes;
  boxes.reserve(patches.size());
  for (const Patch& p : patches) {
    Eigen::AlignedBox3d box;
    for (const Vec3& c : p.corners) box.extend(c);
    boxes.push_back(box);
  }
  return boxes;
}

/// The height of `x` above the plane through `origin` with unit normal `n`, computed as the
/// solver's is_in_front_of does.
double height(const Vec3& x, const Vec3& origin, const Vec3& n) { return n.dot(x - origin); }

}  // namespace

ReceiverCulling::ReceiverCulling(const std::vector<Patch>& patches,
                                 std::vector<char> receives_at_back, double in_plane, bool enabled)
    : patches_(patches),
      receives_at_back_(std::move(receives_at_back)),
      in_plane_(in_plane),
      enabled_(enabled),
      tree_(enabled ? BoxTree<3>(patch_boxes(patches)) : BoxTree<3>()) {}

double ReceiverCulling::highest_above(const Eigen::AlignedBox3d& box, int shooter) const {
  // A linear function's largest value over a box is at the corner that each axis picks.
  const Patch& s = patches_[shooter];
  double h = -s.normal.dot(s.corners[0]);
  for (int i = 0; i < 3; ++i) h += std::max(s.normal[i] * box.min()[i], s.normal[i] * box.max()[i]);
  return h;
}

bool ReceiverCulling::may_receive(int receiver, int shooter) const {
  if (!enabled_) return true;
  const Patch& r = patches_[receiver];
  const Patch& s = patches_[shooter];
  // Some point of the receiver in front of the shooter's plane (beyond the tolerance)...
  const auto above_shooter = [&](const Vec3& c) {
    return height(c, s.corners[0], s.normal) > in_plane_;
  };
  if (std::none_of(r.corners.begin(), r.corners.end(), above_shooter)) return false;
  if (receives_at_back_[receiver]) return true;
  // ...and some point of the shooter in front of the receiver's.
  const auto above_receiver = [&](const Vec3& c) {
    return height(c, r.corners[0], r.normal) > in_plane_;
  };
  return std::any_of(s.corners.begin(), s.corners.end(), above_receiver);
}

void ReceiverCulling::receivers(int shooter, std::vector<int>& out) const {
  out.clear();
  if (!enabled_) {
    out.resize(patches_.size());
    for (size_t p = 0; p < out.size(); ++p) out[p] = static_cast<int>(p);
    return;
  }
  // A box wholly at or behind the shooter's plane (to half the tolerance: the rounding of the
  // box's corners against the patch's own is far below it) holds no receiver that
  // may_receive() would take: its patches' corners all lie within the tolerance.
  tree_.select(
      [&](const Eigen::AlignedBox3d& box) { return highest_above(box, shooter) > 0.5 * in_plane_; },
      [&](int p) {
        if (may_receive(p, shooter)) out.push_back(p);
      });
  // Into index order. Where the receivers are many (half a building faces a wall), marks and
  // one pass over all the patches: the sort of every shot's tens of thousands was 3% of the
  // building's solve, serial.
  if (out.size() * 8 < patches_.size()) {
    std::sort(out.begin(), out.end());
    return;
  }
  marked_.resize(patches_.size(), 0);
  for (const int p : out) marked_[p] = 1;
  out.clear();
  for (size_t p = 0; p < marked_.size(); ++p) {
    if (marked_[p]) out.push_back(static_cast<int>(p)), marked_[p] = 0;
  }
}

}  // namespace rad
