#include "radiosity/near_field.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <limits>

namespace rad {

NearField::NearField(size_t patches, const std::vector<Element>& elements) : roots_(patches) {
  for (size_t e = 0; e < elements.size(); ++e) {
    if (elements[e].parent < 0) roots_[elements[e].patch].push_back(static_cast<int>(e));
  }
  grow(elements);
}

void NearField::grow(const std::vector<Element>& elements) {
  for (size_t e = radius_.size(); e < elements.size(); ++e) {
    radius_.push_back(bounding_sphere(elements[e].corners, elements[e].centroid).radius);
    area_.push_back(elements[e].area);
  }
  stored_.resize(elements.size());
  used_.resize(elements.size());
}

double NearField::average_up(const std::vector<Element>& elements, int patch,
                             std::vector<Rgb>& value, std::vector<float>& spread,
                             const std::vector<char>& buried) const {
  spread.resize(elements.size(), 0.0f);
  const double infinite = std::numeric_limits<double>::infinity();
  // Per subtree: its live leaves' least and largest value (a subtree with none: +inf, -inf).
  struct Range {
    Rgb least, largest;
  };
  // What a live leaf's value can differ from the mean by: the mean counts buried leaves (zero,
  // hidden from every receiver), so it can lie below the live values, and the spread runs
  // over the live values and the mean.
  const auto spread_about = [](const Range& live, const Rgb& mean) {
    if (!(live.least[0] <= live.largest[0])) return 0.0f;  // nothing live: nothing seen
    return static_cast<float>((live.largest.cwiseMax(mean) - live.least.cwiseMin(mean)).maxCoeff());
  };
  const std::function<Range(int)> visit = [&](int node) -> Range {
    const Element& n = elements[node];
    if (n.is_leaf()) {
      if (buried[node]) return {Rgb::Constant(infinite), Rgb::Constant(-infinite)};
      return {value[node], value[node]};
    }
    Rgb sum = Rgb::Zero();
    Range range{Rgb::Constant(infinite), Rgb::Constant(-infinite)};
    for (int c = 0; c < 4; ++c) {
      const Range child = visit(n.first_child + c);
      range.least = range.least.cwiseMin(child.least);
      range.largest = range.largest.cwiseMax(child.largest);
      sum += value[n.first_child + c] * elements[n.first_child + c].area;
    }
    value[node] = sum / n.area;
    spread[node] = spread_about(range, value[node]);
    return range;
  };
  Range whole{Rgb::Constant(infinite), Rgb::Constant(-infinite)};
  Rgb sum = Rgb::Zero();
  double area = 0;
  for (const int root : roots_[patch]) {
    const Range r = visit(root);
    whole.least = whole.least.cwiseMin(r.least);
    whole.largest = whole.largest.cwiseMax(r.largest);
    sum += value[root] * elements[root].area;
    area += elements[root].area;
  }
  return area > 0 ? spread_about(whole, sum / area) : 0.0;
}

Rgb NearField::gather(const std::vector<Element>& elements, int e, int patch,
                      const std::vector<Rgb>& density, const std::vector<float>& spread,
                      double tolerated, const std::function<Rgb(int)>& measure, bool record) {
  const Vec3& x = elements[e].centroid;
  // The receiver's stored pairs with this patch, sorted by node (looked up once per piece per
  // shot). Kept per patch: one list over all patches grew to hundreds of pairs per receiver,
  // and its binary searches and insertions were most of the 11% of CPU this gather took. The
  // patches are searched in an array of their own (tens of them per receiver, a few cache lines).
  StoredPieces& mine = stored_[e];
  const auto at_patch = std::lower_bound(mine.patches.begin(), mine.patches.end(), patch);
  const auto k = at_patch - mine.patches.begin();
  if (at_patch == mine.patches.end() || *at_patch != patch) {
    mine.patches.insert(at_patch, patch);
    mine.pieces.emplace(mine.pieces.begin() + k);
  }
  std::vector<std::pair<int, Eigen::Vector3f>>& stored = mine.pieces[k];
  if (record) used_[e].clear();
  Rgb h = Rgb::Zero();
  std::vector<int> stack(roots_[patch].rbegin(), roots_[patch].rend());
  while (!stack.empty()) {
    const int node = stack.back();
    stack.pop_back();
    if (density[node] == Rgb::Zero()) continue;
    const Element& piece = elements[node];
    const Sphere bounds{piece.centroid, radius_[node]};
    if (!piece.is_leaf() && gathers_in_pieces(x, bounds, piece.area, spread[node], tolerated)) {
      for (int c = 3; c >= 0; --c) stack.push_back(piece.first_child + c);  // children in order
      continue;
    }
    const auto at = std::lower_bound(stored.begin(), stored.end(), node,
                                     [](const auto& entry, int n) { return entry.first < n; });
    Rgb ff;
    if (at != stored.end() && at->first == node) {
      ff = at->second.cast<double>();
    } else {
      ff = measure(node);
      stored.insert(at, {node, ff.cast<float>()});
    }
    h += density[node].cwiseProduct(ff);
    if (record) used_[e].emplace_back(node, ff);
  }
  return h;
}

Rgb NearField::far_density(const std::vector<Element>& elements, int patch,
                           const std::vector<int>& leaves, const std::vector<char>& near,
                           const std::vector<Rgb>& ff, double live_area,
                           const std::vector<Rgb>& density, const Rgb& mean) {
  // sum_e A_e FF_e over every leaf, in parallel over fixed blocks added in block order (the
  // same sum for any thread count; serial, this loop was a twentieth of the solve's wall time).
  Rgb uniform = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<size_t>(0, leaves.size(), 1024), Rgb::Zero().eval(),
      [&](const tbb::blocked_range<size_t>& range, Rgb sum) {
        for (size_t k = range.begin(); k != range.end(); ++k)
          sum += area_[leaves[k]] * ff[leaves[k]];
        return sum;
      },
      [](const Rgb& a, const Rgb& b) { return (a + b).eval(); });
  // Per node, the sum of A_e FF(e, node) over the near receivers (scratch, zero between calls).
  std::vector<Rgb>& sent = sent_;
  sent.resize(elements.size(), Rgb::Zero());
  std::vector<int> touched;
  for (const int e : leaves) {
    if (!near[e]) continue;
    for (const auto& [node, f] : used_[e]) {
      if (sent[node] == Rgb::Zero()) touched.push_back(node);
      sent[node] += area_[e] * f;
    }
  }
  if (touched.empty()) return mean;
  uniform /= live_area;
  const auto sent_by = [&](int node) { return sent[node]; };
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
  for (const int node : touched) sent[node] = Rgb::Zero();
  Rgb out = mean;
  for (int c = 0; c < 3; ++c) {
    if (weights[c] > 0) out[c] = weighted[c] / weights[c];
  }
  return out;
}

}  // namespace rad
