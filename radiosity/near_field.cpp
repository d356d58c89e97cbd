#include "radiosity/near_field.h"

#include <algorithm>

namespace rad {

NearField::NearField(size_t patches, const std::vector<Element>& elements) : roots_(patches) {
  for (size_t e = 0; e < elements.size(); ++e) {
    if (elements[e].parent < 0) roots_[elements[e].patch].push_back(static_cast<int>(e));
  }
  grow(elements.size());
}

void NearField::grow(size_t elements) {
  stored_.resize(std::max(stored_.size(), elements));
  used_.resize(std::max(used_.size(), elements));
}

void NearField::average_up(const std::vector<Element>& elements, int patch,
                           std::vector<Rgb>& value) const {
  const std::function<void(int)> visit = [&](int node) {
    const Element& n = elements[node];
    if (n.is_leaf()) return;
    Rgb sum = Rgb::Zero();
    for (int c = 0; c < 4; ++c) {
      visit(n.first_child + c);
      sum += value[n.first_child + c] * elements[n.first_child + c].area;
    }
    value[node] = sum / n.area;
  };
  for (const int root : roots_[patch]) visit(root);
}

Rgb NearField::gather(const std::vector<Element>& elements, int e, int patch,
                      const std::vector<Rgb>& density, const std::function<Rgb(int)>& measure,
                      bool record) {
  const Vec3& x = elements[e].centroid;
  std::vector<std::pair<int, Eigen::Vector3f>>& stored = stored_[e];
  if (record) used_[e].clear();
  Rgb h = Rgb::Zero();
  const std::function<void(int)> visit = [&](int node) {
    if (density[node] == Rgb::Zero()) return;
    const Element& piece = elements[node];
    if (!piece.is_leaf() && is_near(x, bounding_sphere(piece.corners, piece.centroid))) {
      for (int c = 0; c < 4; ++c) visit(piece.first_child + c);
      return;
    }
    Rgb ff;
    const auto found = std::find_if(stored.begin(), stored.end(),
                                    [&](const auto& entry) { return entry.first == node; });
    if (found != stored.end()) {
      ff = found->second.cast<double>();
    } else {
      ff = measure(node);
      stored.emplace_back(node, ff.cast<float>());
    }
    h += density[node].cwiseProduct(ff);
    if (record) used_[e].emplace_back(node, ff);
  };
  for (const int root : roots_[patch]) visit(root);
  return h;
}

Rgb NearField::far_density(const std::vector<Element>& elements, int patch,
                           const std::vector<int>& leaves, const std::vector<char>& near,
                           const std::vector<Rgb>& ff, double live_area,
                           const std::vector<Rgb>& density, const Rgb& mean) const {
  Rgb uniform = Rgb::Zero();
  std::vector<std::pair<int, Rgb>> sent;  // (node, sum of A_e FF over the near receivers)
  for (const int e : leaves) {
    uniform += elements[e].area * ff[e];
    if (!near[e]) continue;
    for (const auto& [node, f] : used_[e]) sent.emplace_back(node, elements[e].area * f);
  }
  if (sent.empty()) return mean;
  uniform /= live_area;
  std::sort(sent.begin(), sent.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  const auto sent_by = [&](int node) {
    Rgb sum = Rgb::Zero();
    auto it = std::lower_bound(sent.begin(), sent.end(), node,
                               [](const auto& entry, int n) { return entry.first < n; });
    for (; it != sent.end() && it->first == node; ++it) sum += it->second;
    return sum;
  };
  // Down the trees: each leaf's F_near is what the nodes above it sent per unit area.
  Rgb weighted = Rgb::Zero(), weights = Rgb::Zero();
  const std::function<void(int, Rgb)> visit = [&](int node, Rgb near_fraction) {
    const Element& n = elements[node];
    near_fraction += sent_by(node) / n.area;
    if (n.is_leaf()) {
      const Rgb w = (uniform - near_fraction).cwiseMax(0) * n.area;
      weighted += w.cwiseProduct(density[node]);
      weights += w;
      return;
    }
    for (int c = 0; c < 4; ++c) visit(n.first_child + c, near_fraction);
  };
  for (const int root : roots_[patch]) visit(root, Rgb::Zero());
  Rgb out = mean;
  for (int c = 0; c < 3; ++c) {
    if (weights[c] > 0) out[c] = weighted[c] / weights[c];
  }
  return out;
}

}  // namespace rad
