#pragma once
/// The plain values a block's results are made of (doubles, counts, flags), packed one after
/// another into the bytes a worker sends the root (job.h's BlockWork::pack and unpack). Both ends
/// run the same binary, so a value's bytes are the same on both.
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>

#include "scene/error.h"

namespace rad {

class PackedBytes {
 public:
  /// Empty, to put values into; or over `in`, to get them back in the same order.
  explicit PackedBytes(std::string_view in = {}) : in_(in) {}

  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  /// Each of a vector's `n` coefficients (an Eigen vector of doubles: an Rgb, a Vec3).
  template <typename V>
  void put_each(const V& v) {
    for (int c = 0; c < v.size(); ++c) put(v[c]);
  }

  /// Throws Error when fewer bytes remain than the value takes.
  template <typename T>
  void get(T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (in_.size() - at_ < sizeof value) throw Error("a block's bytes are cut short");
    std::memcpy(&value, in_.data() + at_, sizeof value);
    at_ += sizeof value;
  }
  template <typename V>
  void get_each(V& v) {
    for (int c = 0; c < v.size(); ++c) get(v[c]);
  }

  /// True when every byte of the input has been read.
  bool at_end() const { return at_ == in_.size(); }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
  std::string_view in_;
  size_t at_ = 0;
};

}  // namespace rad
