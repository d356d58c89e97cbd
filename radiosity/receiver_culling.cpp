#include "radiosity/receiver_culling.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>
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
      tree_(enabled ? BoxTree<3>(patch_boxes(patches)) : BoxTree<3>()) {
  if (!enabled) return;
  plates_.resize(patches.size());
  for (size_t i = 0; i < patches.size(); ++i) {
    Plate& plate = plates_[i];
    if (patches[i].corners.size() > plate.corners.size())
      throw std::logic_error("ReceiverCulling: a patch of more than 4 corners");
    plate.count = static_cast<int>(patches[i].corners.size());
    std::copy(patches[i].corners.begin(), patches[i].corners.end(), plate.corners.begin());
    plate.normal = patches[i].normal;
  }
}

double ReceiverCulling::highest_above(const Eigen::AlignedBox3d& box, int shooter) const {
  // A linear function's largest value over a box is at the corner that each axis picks.
  const Patch& s = patches_[shooter];
  double h = -s.normal.dot(s.corners[0]);
  for (int i = 0; i < 3; ++i) h += std::max(s.normal[i] * box.min()[i], s.normal[i] * box.max()[i]);
  return h;
}

bool ReceiverCulling::may_receive(int receiver, int shooter) const {
  if (!enabled_) return true;
  const Plate& r = plates_[receiver];
  const Plate& s = plates_[shooter];
  // Some point of the receiver in front of the shooter's plane (beyond the tolerance)...
  const auto above_shooter = [&](const Vec3& c) {
    return height(c, s.corners[0], s.normal) > in_plane_;
  };
  if (std::none_of(r.corners.begin(), r.corners.begin() + r.count, above_shooter)) return false;
  if (receives_at_back_[receiver]) return true;
  // ...and some point of the shooter in front of the receiver's.
  const auto above_receiver = [&](const Vec3& c) {
    return height(c, r.corners[0], r.normal) > in_plane_;
  };
  return std::any_of(s.corners.begin(), s.corners.begin() + s.count, above_receiver);
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
  candidates_.clear();
  tree_.select(
      [&](const Eigen::AlignedBox3d& box) { return highest_above(box, shooter) > 0.5 * in_plane_; },
      [&](int p) { candidates_.push_back(p); });
  // Where the candidates are many (half a building faces a wall), the pairwise test runs in
  // parallel into marks, and one pass over all the patches reads them in index order: the
  // test and the sort of every shot's tens of thousands, serial, were a tenth of the
  // building's solve. Where they are few, serially and a sort. Both give the same list.
  if (candidates_.size() * 8 < patches_.size()) {
    for (const int p : candidates_) {
      if (may_receive(p, shooter)) out.push_back(p);
    }
    std::sort(out.begin(), out.end());
    return;
  }
  marked_.resize(patches_.size(), 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, candidates_.size(), 2048),
                    [&](const tbb::blocked_range<size_t>& range) {
                      for (size_t k = range.begin(); k != range.end(); ++k)
                        marked_[candidates_[k]] = may_receive(candidates_[k], shooter);
                    });
  for (size_t p = 0; p < marked_.size(); ++p) {
    if (marked_[p]) out.push_back(static_cast<int>(p)), marked_[p] = 0;
  }
}

}  // namespace rad
