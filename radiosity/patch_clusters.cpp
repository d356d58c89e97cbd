#include "radiosity/patch_clusters.h"

#include <algorithm>

namespace rad {

std::array<double, kBins> bin_weights(const Vec3& w) {
  std::array<double, kBins> out{};
  for (int i = 0; i < 3; ++i) {
    out[2 * i] = std::max(0.0, w[i]);
    out[2 * i + 1] = std::max(0.0, -w[i]);
  }
  return out;
}

PatchClusters::PatchClusters(const std::vector<Patch>& patches, const std::vector<Vec3>& centroids)
    : patches_(patches), centroids_(centroids) {
  order_.resize(patches.size());
  for (size_t p = 0; p < order_.size(); ++p) order_[p] = static_cast<int>(p);
  if (order_.empty()) return;
  clusters_.emplace_back();
  build(0, 0, static_cast<int>(order_.size()));
  flux_.assign(clusters_.size(), FluxBins{});
}

void PatchClusters::pull(const std::vector<Rgb>& patch_radiosity,
                         const std::vector<double>& live_area) {
  for (size_t i = clusters_.size(); i-- > 0;) {  // children before parents
    const PatchCluster& c = clusters_[i];
    FluxBins& bins = flux_[i];
    if (c.left >= 0) {
      for (int b = 0; b < kBins; ++b) bins[b] = flux_[c.left][b] + flux_[c.left + 1][b];
      continue;
    }
    bins.fill(Rgb::Zero());
    for (int k = c.first; k < c.first + c.count; ++k) {
      const int p = order_[k];
      const std::array<double, kBins> w = bin_weights(patches_[p].normal);
      const Rgb power = patch_radiosity[p] * live_area[p];
      for (int b = 0; b < kBins; ++b) bins[b] += w[b] * power;
    }
  }
}

void PatchClusters::build(int index, int first, int count) {
  Eigen::AlignedBox3d box, centres;
  Vec3 weighted = Vec3::Zero();
  double area = 0;
  for (int i = first; i < first + count; ++i) {
    const Patch& p = patches_[order_[i]];
    for (const Vec3& c : p.corners) box.extend(c);
    centres.extend(centroids_[order_[i]]);
    weighted += p.area * centroids_[order_[i]];
    area += p.area;
  }
  PatchCluster& c = clusters_[index];
  c.box = box;
  c.centre = area > 0 ? Vec3(weighted / area) : box.center();
  c.size = box.diagonal().norm();
  c.first = first;
  c.count = count;
  if (count <= kLeafPatches) {
    std::vector<int> members(order_.begin() + first, order_.begin() + first + count);
    pick_turned(index, members);
    return;
  }
  int axis = 0;
  centres.sizes().maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half,
                   order_.begin() + first + count, [&](int a, int b) {
                     return centroids_[a][axis] < centroids_[b][axis] ||
                            (centroids_[a][axis] == centroids_[b][axis] && a < b);
                   });
  const int left = static_cast<int>(clusters_.size());
  clusters_[index].left = left;
  clusters_.emplace_back();
  clusters_.emplace_back();
  build(left, first, half);
  build(left + 1, first + half, count - half);
  std::vector<int> members;
  for (const int child : {left, left + 1}) {
    for (const auto& bin : clusters_[child].turned) {
      for (const int q : bin) {
        if (q >= 0) members.push_back(q);
      }
    }
  }
  std::sort(members.begin(), members.end());
  members.erase(std::unique(members.begin(), members.end()), members.end());
  pick_turned(index, members);
}
/// PatchCluster::turned from candidate patches (a leaf's own, or its children's picks): per bin,
/// the kClusterRays that lean most its way, ties to the lower index.
void PatchClusters::pick_turned(int index, std::vector<int>& members) {
  for (int b = 0; b < kBins; ++b) {
    const auto lean = [&](int q) { return bin_weights(patches_[q].normal)[b]; };
    std::stable_sort(members.begin(), members.end(), [&](int a, int c) {
      return lean(a) > lean(c) || (lean(a) == lean(c) && a < c);
    });
    auto& picked = clusters_[index].turned[b];
    picked.fill(-1);
    for (int k = 0, n = 0; k < static_cast<int>(members.size()) && n < kClusterRays; ++k) {
      if (lean(members[k]) > 0) picked[n++] = members[k];
    }
  }
}

}  // namespace rad
