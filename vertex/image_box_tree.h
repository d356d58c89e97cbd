#pragma once
/// A bounding-volume hierarchy over axis-aligned boxes in the image plane of a gather point,
/// used by vertex tracing (paper 001 §4) to find the faces around a traced vertex and the pairs
/// of edges that may appear to cross without testing all pairs. Boxes of projected vertices
/// rather than the paper's 3D bounding spheres: the projection is computed per point anyway,
/// convex faces and edges project to convex sets bounded exactly by their vertices' box, and
/// the tolerances are relative to |q| (image coordinates reach 1e8 at the image square).
#include <Eigen/Geometry>
#include <vector>

namespace rad {

using ImageBox = Eigen::AlignedBox2d;

class ImageBoxTree {
 public:
  ImageBoxTree() = default;
  /// Builds over `boxes` (item i has box i). O(n log n).
  explicit ImageBoxTree(std::vector<ImageBox> boxes);

  /// Calls visit(item) for every item whose box intersects `query`.
  template <class Visit>
  void query(const ImageBox& query, Visit&& visit) const {
    visit_until(query, [&](int item) {
      visit(item);
      return false;
    });
  }

  /// Whether any item's box intersects `query`; stops at the first.
  bool any(const ImageBox& query) const {
    return visit_until(query, [](int) { return true; });
  }

  /// Calls visit(a, b) for every item a of this tree and b of `other` whose boxes intersect.
  template <class Visit>
  void pairs(const ImageBoxTree& other, Visit&& visit) const {
    if (nodes_.empty() || other.nodes_.empty()) return;
    std::vector<std::pair<int, int>> stack{{0, 0}};
    while (!stack.empty()) {
      const auto [i, j] = stack.back();
      stack.pop_back();
      const Node& a = nodes_[i];
      const Node& b = other.nodes_[j];
      if (!a.box.intersects(b.box)) continue;
      const bool a_leaf = a.left < 0, b_leaf = other.nodes_[j].left < 0;
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
  /// Calls stop(item) for the items whose box intersects `query` until it returns true;
  /// returns whether it did.
  template <class Stop>
  bool visit_until(const ImageBox& query, Stop&& stop) const {
    if (nodes_.empty()) return false;
    int stack[128];
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

  struct Node {
    ImageBox box;
    int left = -1;  ///< Children at left and left + 1; -1 for a leaf.
    int first = 0;  ///< Leaves: items_[first, first + count).
    int count = 0;
  };
  void build(int index, int first, int count, int depth);

  std::vector<ImageBox> boxes_;
  std::vector<int> items_;
  std::vector<Node> nodes_;
};

}  // namespace rad
