#pragma once
/// The hierarchical solver's clusters (radiosity/hierarchical_solver.h): a binary tree over the
/// patches, each node with its box, its centre, the patches its shadow rays go to, and its flux
/// binned by the six axis directions, so that a receiver far away can take a whole cluster's
/// light through one link (clusters as sources: Smits, Arvo and Greenberg 1994; Sillion 1995).
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "radiosity/solution.h"

namespace rad {

/// Shadow rays from a receiver to a cluster: to the centroids of this many of its patches,
/// each turned to the receiver (PatchCluster::turned).
inline constexpr int kClusterRays = 4;
/// The six axis directions a cluster's flux is binned by: +x, -x, +y, -y, +z, -z.
inline constexpr int kBins = 6;
using FluxBins = std::array<Rgb, kBins>;

/// The weight of each bin toward unit direction w: max(0, +-w_i). A patch of normal n sends
/// its flux B A into the bins by bin_weights(n); a receiver in direction w takes
/// sum_b bin_weights(w)_b x flux_b as the projected flux, exact when the patches face along the
/// axes, at most sqrt(3) times too much for a tilted one (max(0, n.w) <= sum_i max(0, n_i w_i)).
std::array<double, kBins> bin_weights(const Vec3& w);

struct PatchCluster {
  Eigen::AlignedBox3d box;
  Vec3 centre = Vec3::Zero();  ///< Area-weighted centroid of its patches
  double size = 0;             ///< Diagonal of its box
  int left = -1;               ///< Children at left and left + 1; -1 for a leaf
  int first = 0, count = 0;    ///< Its patches: PatchClusters::patch(first .. first + count - 1)
  /// Per bin, up to kClusterRays of its patches whose normals lean most that way (-1: none):
  /// where its shadow rays go. Rays to patches turned away from the receiver would meet what
  /// stands in front of them (the lamp of a back-to-back pair hides the other), and a cluster
  /// seen all blocked would be dropped with the light of its patches that face the receiver.
  std::array<std::array<int, kClusterRays>, kBins> turned;
};

class PatchClusters {
 public:
  /// Median splits of the patches' centroids on the longest axis, kLeafPatches to a leaf;
  /// node 0 is the root, children come after their parents.
  PatchClusters(const std::vector<Patch>& patches, const std::vector<Vec3>& centroids);

  bool empty() const { return clusters_.empty(); }
  int size() const { return static_cast<int>(clusters_.size()); }
  const PatchCluster& operator[](int i) const { return clusters_[i]; }
  /// The k-th patch in the tree's order (a cluster's are consecutive).
  int patch(int k) const { return order_[k]; }
  const FluxBins& flux(int i) const { return flux_[i]; }

  /// Every cluster's flux from the patches' radiosity and live areas: per bin, the sum over its
  /// patches of B A_live bin_weights(n).
  void pull(const std::vector<Rgb>& patch_radiosity, const std::vector<double>& live_area);

 private:
  static constexpr int kLeafPatches = 4;
  void build(int index, int first, int count);
  void pick_turned(int index, std::vector<int>& members);

  const std::vector<Patch>& patches_;
  const std::vector<Vec3>& centroids_;
  std::vector<int> order_;
  std::vector<PatchCluster> clusters_;
  std::vector<FluxBins> flux_;
};

}  // namespace rad
