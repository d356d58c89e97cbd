#include "vertex/image_box_tree.h"

#include <algorithm>

namespace rad {

namespace {
constexpr int kLeafSize = 4;
constexpr int kMaxDepth = 60;  // the query stack holds 2 per level
}  // namespace

ImageBoxTree::ImageBoxTree(std::vector<ImageBox> boxes) : boxes_(std::move(boxes)) {
  items_.resize(boxes_.size());
  for (size_t i = 0; i < items_.size(); ++i) items_[i] = static_cast<int>(i);
  if (!items_.empty()) {
    nodes_.reserve(2 * items_.size() / kLeafSize + 2);
    nodes_.emplace_back();
    build(0, 0, static_cast<int>(items_.size()), 0);
  }
}

void ImageBoxTree::build(int index, int first, int count, int depth) {
  ImageBox box;
  for (int i = first; i < first + count; ++i) box.extend(boxes_[items_[i]]);
  nodes_[index].box = box;
  if (count <= kLeafSize || depth >= kMaxDepth) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return;
  }
  // Median split on the longest axis of the box centres.
  ImageBox centres;
  for (int i = first; i < first + count; ++i) centres.extend(boxes_[items_[i]].center());
  int axis = 0;
  centres.sizes().maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(
      items_.begin() + first, items_.begin() + first + half, items_.begin() + first + count,
      [&](int a, int b) { return boxes_[a].center()[axis] < boxes_[b].center()[axis]; });
  const int left = static_cast<int>(nodes_.size());
  nodes_[index].left = left;
  nodes_.emplace_back();
  nodes_.emplace_back();
  build(left, first, half, depth + 1);
  build(left + 1, first + half, count - half, depth + 1);
}

}  // namespace rad
