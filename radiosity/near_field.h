#pragma once
/// Shooting a patch piece by piece to the receivers near it.
#include <Eigen/Core>
#include <functional>
#include <utility>
#include <vector>

#include "geometry/lambert.h"
#include "radiosity/shooter.h"
#include "radiosity/solution.h"

namespace rad {

/// Progressive radiosity shoots a patch as one polygon of uniform radiosity (its unshot mean).
/// Seen from far, that is what it is; seen from close by (a concave corner, a block's foot),
/// the form factor weights its parts unevenly, and the uniform patch puts light where there is
/// none (a contact shadow) and takes it from where it is. Receivers in a patch's near field
/// therefore gather it piece by piece: its element tree is descended while the receiver is in
/// a node's near field, as hierarchical radiosity refines its links (Hanrahan, Salzman,
/// Aupperle 1991), each node radiating the area-weighted mean of its leaves. Each (receiver,
/// node) form factor is measured once and kept (elements only split: a node never changes).
/// The far receivers then see the patch with the radiosity that keeps the shot's energy (see
/// far_density).
class NearField {
 public:
  /// A receiver is in a piece's near field when its centroid lies within this many bounding
  /// radii of the piece's centroid...
  static constexpr double radii = 3;
  static bool is_near(const Vec3& x, const Sphere& piece) {
    return (x - piece.centre).norm() < radii * piece.radius;
  }
  /// ...or when taking the piece as uniform could be off by more than `tolerated` (irradiance)
  /// at x. Seen as one polygon of its mean radiosity, a piece whose live leaves' radiosities d_l
  /// and mean span [least, largest] sends mean FF instead of sum_l d_l FF_l (buried leaves are
  /// hidden: FF_l = 0); the difference is sum_l (d_l - mean) FF_l, at most
  /// (largest - least) FF in size, and FF is at most
  /// A / (pi gap^2) (gap: from x to the piece's bounding sphere). A piece across a penumbra
  /// seen from a few radii is where this matters; a uniform one never needs it.
  static bool needs_pieces(const Vec3& x, const Sphere& piece, double area, double spread,
                           double tolerated) {
    if (!(spread > 0)) return false;
    return spread * form_factor_bound(area, (x - piece.centre).norm() - piece.radius) > tolerated;
  }
  /// The receiver at x gathers the piece (a patch, or a node of its tree) in pieces: near it,
  /// or where taking it as uniform could cost more than `tolerated`.
  static bool gathers_in_pieces(const Vec3& x, const Sphere& piece, double area, double spread,
                                double tolerated) {
    return is_near(x, piece) || needs_pieces(x, piece, area, spread, tolerated);
  }
  /// The share of the refinement limit (the error a receiver's radiosity may have before it
  /// splits) that the solver lets a piece taken as uniform cost a receiver. Measured on the
  /// Cornell box: a half takes the band of error along the short block's foot (patches past 3
  /// radii across a penumbra) from 1.5% to 0.8% for 6% more CPU time (30% at patch size
  /// 0.16, whose patches span more penumbra); a fifth, a little further, for 13% more; a
  /// twentieth, hardly further, for far more.
  static constexpr double limit_share = 0.5;

  /// Records the top-level elements of every patch (`elements` as made by make_elements).
  NearField(size_t patches, const std::vector<Element>& elements);

  /// Room for every element made so far as a receiver and a piece. Serial.
  void grow(const std::vector<Element>& elements);

  /// Fills the inner nodes of a patch's trees with the area-weighted mean of `value` over their
  /// leaves, and `spread` (per node) with largest - least of `value` over its live leaves (not
  /// `buried`) and its mean, the largest over the channels. Returns the spread of the whole
  /// patch.
  double average_up(const std::vector<Element>& elements, int patch, std::vector<Rgb>& value,
                    std::vector<float>& spread, const std::vector<char>& buried) const;

  /// Sum over the pieces of `patch` that receiver e sees (descending where it is near, or where
  /// a node's spread could make it off by more than `tolerated`) of density(piece) x
  /// FF(e, piece); `measure(node)` is
  /// the visible form factor to a node, called once per pair. With `used`, the pieces and their
  /// form factors are listed there (the receiver's slot, see used()). Thread-safe across
  /// distinct receivers.
  Rgb gather(const std::vector<Element>& elements, int e, int patch,
             const std::vector<Rgb>& density, const std::vector<float>& spread, double tolerated,
             const std::function<Rgb(int)>& measure, bool record);

  /// Whether the patch is one leaf: it has no pieces to gather it by.
  bool is_one_piece(const std::vector<Element>& elements, int patch) const {
    return roots_[patch].size() == 1 && elements[roots_[patch][0]].is_leaf();
  }

  /// f(leaf) for each leaf of a patch's trees.
  template <typename F>
  void for_each_leaf(const std::vector<Element>& elements, int patch, const F& f) const {
    std::vector<int> stack(roots_[patch].rbegin(), roots_[patch].rend());
    while (!stack.empty()) {
      const int node = stack.back();
      stack.pop_back();
      if (elements[node].is_leaf()) {
        f(node);
      } else {
        for (int c = 3; c >= 0; --c) stack.push_back(elements[node].first_child + c);
      }
    }
  }

  /// Element e's bounding radius about its centroid (kept since grow()).
  double radius(int e) const { return radius_[e]; }

  /// The pieces receiver e used in its last recorded gather.
  const std::vector<std::pair<int, Rgb>>& used(int e) const { return used_[e]; }

  /// The radiosity the far receivers should see the patch with. If they took its mean, the
  /// shot would deliver sum_l A_l (mean - d_l) F_far(l) less than it sends (d_l a leaf's
  /// radiosity, F_far(l) the fraction of its light that goes to far receivers): pieces at a
  /// concave edge send much of theirs to the near wall, and are the darker ones, so that sum is
  /// a loss (0.4% of the light in a closed room). The mean is therefore weighted by
  /// F_far(l) = U - F_near(l), with U the fraction of the patch's light its receivers get as
  /// a uniform patch (sum_e A_e FF_e / A_live, `ff` per element) and F_near(l) what the near
  /// receivers (`near`) took from leaf l and the nodes above it (by reciprocity, A_e FF(e,
  /// node) / A_node). Returns `mean` when no receiver is near.
  Rgb far_density(const std::vector<Element>& elements, int patch, const std::vector<int>& leaves,
                  const std::vector<char>& near, const std::vector<Rgb>& ff, double live_area,
                  const std::vector<Rgb>& density, const Rgb& mean);

 private:
  std::vector<std::vector<int>> roots_;  ///< Per patch, its top-level elements
  /// The form factors from a receiver to the pieces of the patches it gathered in pieces.
  struct StoredPieces {
    std::vector<int> patches;  ///< Sorted
    /// Per patch in `patches`: (node, form factor), sorted by node.
    std::vector<std::vector<std::pair<int, Eigen::Vector3f>>> pieces;
  };
  std::vector<StoredPieces> stored_;                    ///< Per receiver
  std::vector<std::vector<std::pair<int, Rgb>>> used_;  ///< Per receiver
  std::vector<Rgb> sent_;                               ///< far_density's scratch, per node
  std::vector<double> radius_;  ///< Per element, its bounding radius about its centroid
  /// Per element, its area: far_density sums over every leaf at every shot, and this array
  /// is what that loop reads (an Element is two cache lines; an area is an eighth of one).
  std::vector<double> area_;
};

}  // namespace rad
