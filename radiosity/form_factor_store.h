#pragma once
/// The visible form factors a solve has measured, kept for the shots that follow.
#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <vector>

#include "geometry/vec.h"

namespace rad {

/// Per shooting patch, its visible form factor to each element, as first measured. A pair's
/// form factor does not change between shots (the patch, the receiver and what lies between
/// stay), so a patch shooting again, or a new element re-gathering, reuses it: the same value
/// with the same jitter, and no rays. Single precision (relative 6e-8, far below the shadow
/// rays' sampling error). Kept while it fits in `budget` bytes; past it, patches measure afresh.
class FormFactorStore {
 public:
  explicit FormFactorStore(size_t budget) : budget_(budget) {}

  /// Makes room for `elements` receivers of `patch` (of `patches`), unless the budget is spent.
  /// Serial: parallel loops only read and fill slots.
  void grow(int patch, size_t patches, size_t elements) {
    if (stored_.size() < patches) stored_.resize(patches);
    std::vector<Eigen::Vector3f>& store = stored_[patch];
    if (store.size() >= elements) return;
    const size_t more = (elements - store.size()) * sizeof(Eigen::Vector3f);
    if (bytes_ + more > budget_) return;
    store.resize(elements, Eigen::Vector3f::Constant(std::nanf("")));
    bytes_ += more;
  }
  /// The stored value of (patch, element), if any.
  bool find(int patch, int element, Rgb* ff) const {
    if (static_cast<size_t>(patch) >= stored_.size()) return false;
    const std::vector<Eigen::Vector3f>& store = stored_[patch];
    if (static_cast<size_t>(element) >= store.size() || std::isnan(store[element][0])) return false;
    *ff = store[element].cast<double>();
    return true;
  }
  /// Keeps the value of (patch, element) when there is room for it.
  void put(int patch, int element, const Rgb& ff) {
    if (static_cast<size_t>(patch) >= stored_.size()) return;
    std::vector<Eigen::Vector3f>& store = stored_[patch];
    if (static_cast<size_t>(element) < store.size()) store[element] = ff.cast<float>();
  }

 private:
  size_t budget_;
  size_t bytes_ = 0;
  std::vector<std::vector<Eigen::Vector3f>> stored_;
};

}  // namespace rad
