#pragma once
/// A bounding-volume hierarchy over axis-aligned boxes, in 2D (vertex tracing's image plane,
/// vertex/image_box_tree.h) or 3D (the solver's shaft culling, radiosity/shadow_culling.h). Median
/// splits on the longest axis of the box centres; leaves of a few items. A query visits what its
/// box meets, so finding the items near a small box costs O(log n + k) rather than a pass over all
/// n.
#include <Eigen/Geometry>
#include <algorithm>
#include <utility>
#include <vector>

namespace rad {

template <int Dim>
class BoxTree {
 public:
  using Box = Eigen::AlignedBox<double, Dim>;

  BoxTree() = default;
  /// Builds over `boxes` (item i has box i). O(n log n).
  explicit BoxTree(std::vector<Box> boxes) : boxes_(std::move(boxes)) {
    items_.resize(boxes_.size());
    for (size_t i = 0; i < items_.size(); ++i) items_[i] = static_cast<int>(i);
    if (!items_.empty()) {
      nodes_.reserve(2 * items_.size() / kLeafSize + 2);
      nodes_.emplace_back();
      build(0, 0, static_cast<int>(items_.size()), 0);
    }
  }

  const Box& box(int item) const { return boxes_[item]; }

  /// Calls visit(item) for every item whose box intersects `query`.
  template <class Visit>
  void query(const Box& query, Visit&& visit) const {
    any_of(query, [&](int item) {
      visit(item);
      return false;
    });
  }

  /// Whether stop(item) is true of any item whose box intersects `query`; asks those items in
  /// an unspecified order and stops at the first true.
  template <class Stop>
  bool any_of(const Box& query, Stop&& stop) const {
    if (nodes_.empty()) return false;
    int stack[2 * kMaxDepth + 2];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (!node.box.intersects(query)) continue;
      if (node.left < 0) {
        for (int i = node.first; i < node.first + node.count; ++i) {
          if (boxes_[items_[i]].intersects(query) && stop(items_[i])) return true;
        }
      } else {
        stack[top++] = node.left;
        stack[top++] = node.left + 1;
      }
    }
    return false;
  }

  /// Walks the tree nearest first from `point` (by the distance to a box; a box holding the
  /// point is at distance 0): enter(box) is asked of each node reached, and only a node it
  /// accepts is opened; the items of opened leaves go to visit(item), in order of the distance
  /// to their boxes (nodes and items share one queue). A visit may change what enter answers
  /// next (an occlusion walk inserts what it sees), which is why the order is nearest first.
  template <class Enter, class Visit>
  void nearest_first(const Eigen::Matrix<double, Dim, 1>& point, Enter&& enter,
                     Visit&& visit) const {
    if (nodes_.empty()) return;
    // (squared distance, node index, or -1 - item for an item); nearer first, then by index.
    using Entry = std::pair<double, int>;
    std::vector<Entry> heap{{nodes_[0].box.squaredExteriorDistance(point), 0}};
    const auto farther = [](const Entry& a, const Entry& b) { return a > b; };
    const auto push = [&](double distance, int entry) {
      heap.emplace_back(distance, entry);
      std::push_heap(heap.begin(), heap.end(), farther);
    };
    while (!heap.empty()) {
      std::pop_heap(heap.begin(), heap.end(), farther);
      const int entry = heap.back().second;
      heap.pop_back();
      if (entry < 0) {
        visit(-1 - entry);
        continue;
      }
      const Node& node = nodes_[entry];
      if (!enter(node.box)) continue;
      if (node.left >= 0) {
        for (const int child : {node.left, node.left + 1})
          push(nodes_[child].box.squaredExteriorDistance(point), child);
        continue;
      }
      for (int i = node.first; i < node.first + node.count; ++i)
        push(boxes_[items_[i]].squaredExteriorDistance(point), -1 - items_[i]);
    }
  }

  /// Calls visit(item) for every item whose box `accept` takes, opening only the nodes whose
  /// boxes it takes: for a test that holds of a box whenever it holds of a box inside it (a
  /// half-space that a box reaches into), in O(log n + k) where a query box will not do.
  template <class Accept, class Visit>
  void select(Accept&& accept, Visit&& visit) const {
    if (nodes_.empty()) return;
    int stack[2 * kMaxDepth + 2];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (!accept(node.box)) continue;
      if (node.left < 0) {
        for (int i = node.first; i < node.first + node.count; ++i) {
          if (accept(boxes_[items_[i]])) visit(items_[i]);
        }
      } else {
        stack[top++] = node.left + 1;
        stack[top++] = node.left;
      }
    }
  }

  /// Whether any item's box intersects `query`; stops at the first.
  bool any(const Box& query) const {
    return any_of(query, [](int) { return true; });
  }

  /// Calls visit(a, b) for every item a of this tree and b of `other` whose boxes intersect.
  template <class Visit>
  void pairs(const BoxTree& other, Visit&& visit) const {
    if (nodes_.empty() || other.nodes_.empty()) return;
    std::vector<std::pair<int, int>> stack{{0, 0}};
    while (!stack.empty()) {
      const auto [i, j] = stack.back();
      stack.pop_back();
      const Node& a = nodes_[i];
      const Node& b = other.nodes_[j];
      if (!a.box.intersects(b.box)) continue;
      const bool a_leaf = a.left < 0, b_leaf = b.left < 0;
      if (a_leaf && b_leaf) {
        for (int p = a.first; p < a.first + a.count; ++p) {
          for (int q = b.first; q < b.first + b.count; ++q) {
            if (boxes_[items_[p]].intersects(other.boxes_[other.items_[q]]))
              visit(items_[p], other.items_[q]);
          }
        }
      } else if (b_leaf || (!a_leaf && a.box.volume() >= b.box.volume())) {
        stack.emplace_back(a.left, j);
        stack.emplace_back(a.left + 1, j);
      } else {
        stack.emplace_back(i, b.left);
        stack.emplace_back(i, b.left + 1);
      }
    }
  }

 private:
  static constexpr int kLeafSize = 4;
  static constexpr int kMaxDepth = 60;  // the query stack holds 2 per level

  struct Node {
    Box box;
    int left = -1;  ///< Children at left and left + 1; -1 for a leaf.
    int first = 0;  ///< Leaves: items_[first, first + count).
    int count = 0;
  };

  void build(int index, int first, int count, int depth) {
    Box box;
    for (int i = first; i < first + count; ++i) box.extend(boxes_[items_[i]]);
    nodes_[index].box = box;
    if (count <= kLeafSize || depth >= kMaxDepth) {
      nodes_[index].first = first;
      nodes_[index].count = count;
      return;
    }
    // Median split on the longest axis of the box centres.
    Box centres;
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

  std::vector<Box> boxes_;
  std::vector<int> items_;
  std::vector<Node> nodes_;
};

}  // namespace rad
