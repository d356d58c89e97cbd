#pragma once
/// The visible form factors a solve has measured, kept for the shots that follow.
#include <sys/mman.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <vector>

#include "geometry/vec.h"

namespace rad {

/// Per shooting patch, its visible form factor to each element, as first measured. A pair's
/// form factor does not change between shots (the patch, the receiver and what lies between
/// stay), so a patch shooting again, or a new element re-gathering, reuses it: the same value
/// with the same jitter, and no rays. Single precision (relative 6e-8, far below the shadow
/// rays' sampling error). Kept while it fits in `budget` bytes; past it, patches measure afresh.
///
/// A patch's values sit in fixed blocks of `block` elements, made only for the receivers its
/// shots and re-gathers reach, and never moved: a split adds a few elements, and one array per
/// patch resized to the element count was copied and faulted in afresh as it grew; and a floor
/// triangle that reaches only the lamp's elements needs one small block, not all of them. The
/// blocks are cut from arenas of huge pages where the kernel offers them (transparent huge
/// pages on request): the Cornell box's store, every block made, was 0.25 GB, 60,000 page
/// faults in 4 KiB pages, all taken in the serial part of a shot.
class FormFactorStore {
 public:
  static constexpr size_t block = 512;

  explicit FormFactorStore(size_t budget) : budget_(budget) {}

  /// Makes room for `elements` receivers of `patch` (of `patches`), unless the budget is spent.
  /// Serial: parallel loops only read and fill slots.
  void grow(int patch, size_t patches, size_t elements) {
    for (size_t b = 0; b * block < elements; ++b) {
      if (!add_block(patch, patches, b)) return;
    }
  }
  /// Makes room for the receivers `which` of `patch` only (the blocks that hold them), unless
  /// the budget is spent: a shot that reaches a few receivers stores no others' slots.
  void grow(int patch, size_t patches, const std::vector<int>& which) {
    for (const int e : which) {
      if (!add_block(patch, patches, static_cast<size_t>(e) / block)) return;
    }
  }
  /// The stored value of (patch, element), if any.
  bool find(int patch, int element, Rgb* ff) const {
    const Eigen::Vector3f* slot = at(patch, element);
    if (slot == nullptr || std::isnan((*slot)[0])) return false;
    *ff = slot->cast<double>();
    return true;
  }
  /// Keeps the value of (patch, element) when there is room for it.
  void put(int patch, int element, const Rgb& ff) {
    if (Eigen::Vector3f* slot = at(patch, element)) *slot = ff.cast<float>();
  }
  /// Bytes held.
  size_t bytes() const { return bytes_; }

 private:
  static constexpr size_t block_bytes = block * sizeof(Eigen::Vector3f);
  Eigen::Vector3f* at(int patch, int element) const {
    if (static_cast<size_t>(patch) >= stored_.size()) return nullptr;
    const auto& blocks = stored_[patch];
    const size_t b = static_cast<size_t>(element) / block;
    return b < blocks.size() && blocks[b] != nullptr
               ? &blocks[b][static_cast<size_t>(element) % block]
               : nullptr;
  }

  /// Block b of `patch` (of `patches`), made if it is not there yet and the budget allows;
  /// false when the budget or the system's memory is spent.
  bool add_block(int patch, size_t patches, size_t b) {
    if (stored_.size() < patches) stored_.resize(patches);
    std::vector<Eigen::Vector3f*>& blocks = stored_[patch];
    if (b < blocks.size() && blocks[b] != nullptr) return true;
    if (bytes_ + block_bytes > budget_) return false;
    Eigen::Vector3f* values = new_block();
    if (values == nullptr) return false;
    std::fill_n(values, block, Eigen::Vector3f::Constant(std::nanf("")));
    if (blocks.size() <= b) blocks.resize(b + 1, nullptr);
    blocks[b] = values;
    bytes_ += block_bytes;
    return true;
  }

  /// A block from the current arena, a new arena when it is full; null when the system has
  /// no memory to give (the pairs then go unstored).
  Eigen::Vector3f* new_block() {
    if (arenas_.empty() || arena_used_ + block_bytes > arena_bytes) {
      void* memory = mmap(nullptr, arena_bytes, PROT_READ | PROT_WRITE,
                          MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
      if (memory == MAP_FAILED) return nullptr;
      madvise(memory, arena_bytes, MADV_HUGEPAGE);  // a request: ignored where unsupported
      arenas_.emplace_back(static_cast<char*>(memory));
      arena_used_ = 0;
    }
    char* out = arenas_.back().get() + arena_used_;
    arena_used_ += block_bytes;
    return reinterpret_cast<Eigen::Vector3f*>(out);
  }
  static constexpr size_t arena_bytes = size_t(32) << 20;  ///< 16 huge pages of 2 MiB
  struct Unmap {
    void operator()(char* memory) const { munmap(memory, arena_bytes); }
  };

  size_t budget_;
  size_t bytes_ = 0;
  std::vector<std::vector<Eigen::Vector3f*>> stored_;  ///< Per patch, its blocks (null: none)
  std::vector<std::unique_ptr<char, Unmap>> arenas_;
  size_t arena_used_ = 0;  ///< Bytes of the last arena handed out
};

}  // namespace rad
