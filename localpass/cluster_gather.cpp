// One point's gather by clusters (LocalPass::ClusterGather): the error-bounded sum of 004 Fig. 6
// over the cluster tree, each term in a certified interval (localpass/cluster_bounds.h), refined
// widest first until the stopping rule holds.
#include <algorithm>
#include <numbers>
#include <optional>

#include "geometry/lambert.h"
#include "geometry/tolerance.h"
#include "hemisphere/blocker_surface.h"
#include "localpass/cluster_bounds.h"
#include "localpass/local_pass.h"

namespace rad {

/// The state of one gather. The sum H = exact + sum of heap terms + sum of pending terms +
/// gathered, each in its interval: `exact` for faces seen whole (Lambert's formula), the heap
/// for clusters not yet refined, `pending` for faces that may be hidden ([0, hi]), `gathered`
/// for the exact gather's total so far.
class LocalPass::ClusterGather {
 public:
  ClusterGather(const LocalPass& pass, const Vec3& x, const Vec3& n, double tolerance,
                const GatherScope& scope)
      : pass_(pass),
        scope_(scope),
        clusters_(pass.clusters_.clusters()),
        x_(x),
        n_(n),
        tolerance_(tolerance),
        exact_only_(!(tolerance > 0)),
        queries_(!pass.blocker_pieces_.empty()),
        faces_by_query_(queries_ && pass.faces_by_query_),
        exact_(scope.known_lo),
        known_width_(scope.known_hi - scope.known_lo) {}

  LocalPassResult run() {
    add_roots();
    while (!done()) {
      if (!heap_.empty() &&
          (exact_only_ || pending_.empty() || heap_.front().width >= pending_.front().width)) {
        refine_widest_cluster();
      } else {
        gather_widest_faces();
      }
    }
    if (session_) result_.projected += session_->projected();
    // The interval of the sum, from the terms themselves (the running sums drift by rounding).
    Rgb lo = exact_ + gathered_, hi = exact_ + gathered_ + known_width_;
    for (const Term& t : heap_) lo += t.lo, hi += t.hi;
    for (const Term& t : pending_) hi += t.hi;
    result_.bound = 0.5 * (hi - lo);
    result_.irradiance = 0.5 * (hi + lo);
    return result_;
  }

 private:
  /// A term of the sum with its certified interval, per channel: lo <= exact term <= hi.
  struct Term {
    double width = 0;                          ///< max_c (hi - lo): the refinement order
    int index = -1;                            ///< Cluster (heap) or face (pending)
    int blockers_begin = 0, blockers_end = 0;  ///< Its blockers in the call's pool; none: whole
    Rgb lo = Rgb::Zero(), hi = Rgb::Zero();
    bool seen_whole() const { return blockers_begin == blockers_end; }
  };
  /// Widest first; ties by index, so that the order (and the image) does not depend on threads.
  static bool narrower(const Term& a, const Term& b) {
    return a.width != b.width ? a.width < b.width : a.index > b.index;
  }

  /// The roots of the sum: the root cluster of every polygon x may see (localpass/visible_set.h;
  /// without the visibility culling, the whole scene), each with its blockers among the
  /// candidates; or the scope's clusters, those known to be seen whole as they are and the
  /// others culled alike (a polygon x cannot see contributes nothing).
  void add_roots() {
    if (scope_.whole) {
      for (const int c : *scope_.whole) add(c, 0, 0);
    }
    if (scope_.given_roots() && (!scope_.culled || scope_.culled->empty())) return;
    std::vector<int> seen;
    if (pass_.visible_set_) {
      seen = pass_.visible_set_->polygons(x_, n_);
      result_.visible_polygons = static_cast<int>(seen.size());
    }
    const std::vector<int> candidates = pass_.visible_set_ ? pass_.culling_.candidates(x_, n_, seen)
                                                           : pass_.culling_.candidates(x_, n_);
    const auto add_root = [&](int root) {
      const Cluster& cluster = clusters_[root];
      if (!pass_.culling_.in_front_of_polygon(cluster.polygon, x_)) return;  // cannot light x
      pass_.culling_.blockers(candidates, x_, cluster.box, cluster.outline, cluster.polygon,
                              &scratch_);
      add_with_scratch_blockers(root);
    };
    if (scope_.given_roots()) {
      for (const int c : *scope_.culled) {
        if (!pass_.visible_set_ || std::ranges::binary_search(seen, clusters_[c].polygon))
          add_root(c);
      }
    } else if (pass_.visible_set_) {
      for (const int p : seen)
        if (pass_.root_of_polygon_[p] >= 0) add_root(pass_.root_of_polygon_[p]);
    } else {
      for (const int root : pass_.clusters_.roots()) add_root(root);
    }
  }

  /// Adds cluster c with the blockers the last culling query left in scratch_.
  void add_with_scratch_blockers(int c) {
    const int own = static_cast<int>(pool_.size());
    pool_.insert(pool_.end(), scratch_.begin(), scratch_.end());
    add(c, own, static_cast<int>(pool_.size()));
  }

  /// Cluster c under a parent whose blockers are pool[begin, end): its own are among them.
  void add_child(int c, int begin, int end) {
    if (begin == end) return add(c, begin, end);
    const Cluster& cluster = clusters_[c];
    // A face under a partly hidden cluster: a query with the parent's blockers (a superset of
    // its own) is exact and costs about what the shafts would, so skip them.
    if (cluster.is_leaf() && faces_by_query_) return add(c, begin, end);
    pass_.culling_.blockers(std::span<const int>(pool_.data() + begin, pool_.data() + end), x_,
                            cluster.box, cluster.outline, cluster.polygon, &scratch_);
    add_with_scratch_blockers(c);
  }

  /// The visible form factor of the cluster's outline through the blockers pool[begin, end),
  /// by an exact visibility query: every blocker opaque, or (`without_filters`) the opaque ones
  /// alone. The two bracket what passes through filters. Blockers are inserted into the two
  /// surfaces as they are first named.
  double visible_form_factor(const Cluster& cluster, int begin, int end, bool without_filters) {
    std::optional<BlockerSurface>& surface = surfaces_[without_filters];
    std::vector<char>& in = inserted_[without_filters];
    if (!surface) {
      surface.emplace(x_, n_, pass_.tolerance_);
      in.assign(pass_.blocker_pieces_.size(), 0);
    }
    for (int i = begin; i < end; ++i) {
      if (in[pool_[i]]) continue;
      in[pool_[i]] = 1;
      if (without_filters && pass_.filter_polygon_[pool_[i]]) continue;
      for (const EmittingFace& piece : pass_.blocker_pieces_[pool_[i]]) {
        surface->add(piece.polygon, piece.vertices, piece.normal);
        ++result_.projected;
      }
    }
    ++result_.projected;
    return surface->visible_form_factor(cluster.polygon, cluster.outline, cluster.normal);
  }

  /// Adds cluster c, seen by x whole or through the blockers listed in pool[begin, end): a face
  /// known exactly goes to `exact`, a face that may be hidden to `pending`, a cluster to the
  /// heap with its interval (or, at tolerance 0 and seen whole, its faces to `exact`).
  void add(int c, int begin, int end) {
    const Cluster& cluster = clusters_[c];
    const double ff = point_polygon_form_factor(x_, n_, cluster.outline);
    if (!(ff > 0) || !(cluster.bmax.maxCoeff() > 0)) return;  // contributes nothing
    Term t{0, c, begin, end, Rgb::Zero(), cluster.bmax * ff};
    // What may be hidden, when queries are at hand: its visible form factor, exactly.
    // (At tolerance 0 a partly hidden cluster is only a way down to its faces: no query.)
    // Through filters, the visible form factor with them opaque (`visible`, for the lower
    // ends) and without them (`visible_hi`, for the upper ends): see the header. A face seen
    // through a filter is never exact by a query.
    const bool through_filter = std::any_of(pool_.begin() + begin, pool_.begin() + end,
                                            [&](int p) { return pass_.filter_polygon_[p] != 0; });
    const bool query = !t.seen_whole() && queries_ &&
                       (cluster.is_leaf() ? faces_by_query_ && !through_filter : !exact_only_);
    // What is visible of the outline is part of it: a query above ff is rounding or a defect
    // of the visibility structure (issue 36 found one), and must not raise a lower end.
    const double visible =
        query ? std::min(ff, visible_form_factor(cluster, begin, end, false)) : ff;
    const double visible_hi = query && through_filter
                                  ? std::min(ff, visible_form_factor(cluster, begin, end, true))
                                  : visible;
    const bool known = t.seen_whole() || query;
    if (cluster.is_leaf() && known) {  // exact: B FF(x, visible part of the face)
      exact_ += pass_.faces_[cluster.face].exitance * visible;
      ++result_.gathered_exactly;
      if (t.seen_whole()) ++result_.unoccluded;
      return;
    }
    if (cluster.is_leaf()) {
      t.index = cluster.face;
      t.width = t.hi.maxCoeff();
      pending_.push_back(t);
      std::push_heap(pending_.begin(), pending_.end(), narrower);
      pending_hi_ += t.hi, pending_width_ += t.width;
      return;
    }
    if (exact_only_ && t.seen_whole()) return add_faces_exactly(cluster);
    ++result_.clusters;
    bound_cluster(cluster, ff, visible, visible_hi, known, query, t);
    heap_.push_back(t);
    std::push_heap(heap_.begin(), heap_.end(), narrower);
    heap_lo_ += t.lo, heap_hi_ += t.hi, heap_width_ += t.width;
  }

  /// At tolerance 0 every face of a cluster seen whole will be summed: sum them now.
  void add_faces_exactly(const Cluster& cluster) {
    for (int i = 0; i < cluster.face_count; ++i) {
      const int f = pass_.clusters_.faces()[cluster.first_face + i];
      const EmittingFace& face = pass_.faces_[f];
      const double face_ff = point_polygon_form_factor(x_, n_, face.vertices);
      if (!(face_ff > 0) || !(face.exitance.maxCoeff() > 0)) continue;
      exact_ += face.exitance * face_ff;
      ++result_.gathered_exactly, ++result_.unoccluded;
    }
  }

  /// The certified interval of a cluster's term sum B_A FF_A over its faces A, into t.lo and
  /// t.hi (t.hi starts at bmax ff), from its unoccluded form factor ff and, when `known`, the
  /// visible one (`visible`; `visible_hi` with filters left out).
  void bound_cluster(const Cluster& cluster, double ff, double visible, double visible_hi,
                     bool known, bool query, Term& t) const {
    // Its faces' form factors sum to FF(x, their union) <= FF(x, outline) = ff; seen whole and
    // filling its outline, the sum is also >= ff minus what the gap can subtend.
    const double h = cluster.normal.dot(x_ - cluster.outline.front());
    const double ff_lo =
        known && cluster.fills_outline
            ? std::max(0.0, visible - cluster.gap_area / (std::numbers::pi * h * h))
            : 0.0;
    t.lo = cluster.bmin * ff_lo;  // zeroth order: bmin sum FF_A <= term <= bmax sum FF_A
    t.hi = cluster.bmax * visible_hi;
    // First order: with kmin <= k <= kmax on the outline (cluster_bounds.h), the term
    // sum B_A FF_A = bmean sum FF_A + sum (B_A - bmean) (FF_A - area_A kmid), since
    // sum (B_A - bmean) area_A = 0; each |FF_A - area_A kmid| <= area_A (kmax - kmin) / 2.
    const KernelBounds kernel = kernel_bounds(cluster, x_, n_, h);
    const Rgb slack = cluster.babs * (0.5 * (kernel.kmax - kernel.kmin));
    if (kernel.above_horizon) {
      // Second order: with k = k(c) + g . (y - c) + R on the outline, |R| <= remainder,
      // FF_A - area_A k(c) = g . area_A (c_A - c) + integral of R over A, so the term is
      // bmean sum FF_A + g . moment within babs remainder (again sum (B_A - bmean) area_A = 0).
      const Rgb second = cluster.babs * kernel.remainder;
      const Rgb linear = (kernel.gradient.transpose() * cluster.moment).transpose();
      if (t.seen_whole()) t.lo = t.lo.cwiseMax(cluster.bmean * ff_lo + linear - second);
      t.hi = t.hi.cwiseMin(cluster.bmean * ff + linear + second);
    }
    if (t.seen_whole()) t.lo = t.lo.cwiseMax(cluster.bmean * ff_lo - slack);
    // Hidden parts only lower the term: the upper end holds whether it is seen whole or not.
    t.hi = t.hi.cwiseMin(cluster.bmean * ff + slack);
    if (query) {
      // Partly hidden, with V = visible known: the term is bmean sum FF'_A + sum (B_A - bmean)
      // FF'_A over the faces' visible parts, with sum FF'_A in [ff_lo, V] and each
      // FF'_A <= area_A kmax, so it is within babs kmax of bmean sum FF'_A. (Through filters
      // FF'_A weighs the kernel by what passes, in [0, 1], and the sum lies in
      // [ff_lo, visible_hi].)
      const Rgb spread = cluster.babs * kernel.kmax;
      t.lo = t.lo.cwiseMax(cluster.bmean * ff_lo - spread);
      t.hi = t.hi.cwiseMin(cluster.bmean * visible_hi + spread);
    }
    t.lo = t.lo.cwiseMin(t.hi);  // the two agree but for rounding
    t.width = (t.hi - t.lo).maxCoeff();
  }

  /// The stopping rule (004 Fig. 6): the interval's half width at most T times its midpoint
  /// (brightest channel). At tolerance 0, only when nothing is left to refine.
  bool done() const {
    if (heap_.empty() && pending_.empty()) return true;
    if (exact_only_) return false;
    const Rgb lo = exact_ + heap_lo_ + gathered_;
    const Rgb hi = exact_ + heap_hi_ + gathered_ + pending_hi_ + known_width_;
    return 0.5 * (hi - lo).maxCoeff() <= tolerance_ * (0.5 * (hi + lo)).maxCoeff();
  }

  /// Refines the widest cluster: its children's intervals replace its own.
  void refine_widest_cluster() {
    std::pop_heap(heap_.begin(), heap_.end(), narrower);
    const Term t = heap_.back();
    heap_.pop_back();
    heap_lo_ -= t.lo, heap_hi_ -= t.hi, heap_width_ -= t.width;
    for (const int child : clusters_[t.index].children)
      add_child(child, t.blockers_begin, t.blockers_end);
  }

  /// What the pending widths may sum to after the next exact gather step.
  double pending_target() const {
    if (exact_only_) return -1;                                       // all of them, in one step
    if (pass_.gatherer_->incremental()) return 0.5 * pending_width_;  // small steps cost nothing
    // Each step starts afresh: aim straight at the stopping rule, with what is known of H
    // (the whole width may be 2 T H / (1 - T); H is at least the lower end).
    const double h_lo = (exact_ + heap_lo_ + gathered_).maxCoeff();
    return std::max(
        0.0, 2 * tolerance_ * h_lo / std::max(1 - tolerance_, relative::kRounding) - heap_width_);
  }

  /// Gathers the widest pending faces exactly, with whatever may hide them.
  void gather_widest_faces() {
    const double target = pending_target();
    std::vector<OcclusionSplit::Group> groups;  // by polygon, for the occluder search
    std::vector<int> group_polygon, radiating;
    do {
      std::pop_heap(pending_.begin(), pending_.end(), narrower);
      const Term t = pending_.back();
      pending_.pop_back();
      pending_hi_ -= t.hi, pending_width_ -= t.width;
      radiating.push_back(t.index);
      const int polygon = pass_.faces_[t.index].polygon;
      const size_t g = std::ranges::find(group_polygon, polygon) - group_polygon.begin();
      if (g == group_polygon.size()) group_polygon.push_back(polygon), groups.emplace_back();
      OcclusionSplit::Group* group = &groups[g];
      group->faces.push_back(t.index);
      group->box.extend(bounding_box(pass_.faces_[t.index].vertices));
      group->blockers.insert(group->blockers.end(), pool_.begin() + t.blockers_begin,
                             pool_.begin() + t.blockers_end);
    } while (!pending_.empty() && pending_width_ > target);
    if (pending_.empty()) pending_hi_ = Rgb::Zero(), pending_width_ = 0;  // no rounding residue
    std::vector<int> occluders;
    for (OcclusionSplit::Group& group : groups) {
      std::ranges::sort(group.blockers);
      group.blockers.erase(std::unique(group.blockers.begin(), group.blockers.end()),
                           group.blockers.end());
      pass_.culling_.occluders(x_, group, &occluders);
    }
    if (!session_) session_ = pass_.gatherer_->start(x_, n_);
    gathered_ = session_->step(radiating, occluders).irradiance;
    result_.gathered_exactly += static_cast<int>(radiating.size());
    ++result_.gathers;
  }

  const LocalPass& pass_;
  const GatherScope& scope_;
  const std::vector<Cluster>& clusters_;
  const Vec3 x_, n_;
  const double tolerance_;  ///< The stopping rule's relative tolerance.
  const bool exact_only_;
  /// The hemisphere method: what may be hidden is resolved by exact visibility queries against
  /// the blocking polygons. Faces that may be hidden: by a query too (hemisphere), or by the
  /// method's own gather (vertex tracing).
  const bool queries_, faces_by_query_;

  LocalPassResult result_;
  Rgb exact_;
  Rgb known_width_;  ///< The scope's known part: exact_ starts at its lower end
  Rgb heap_lo_ = Rgb::Zero(), heap_hi_ = Rgb::Zero();
  Rgb pending_hi_ = Rgb::Zero();
  Rgb gathered_ = Rgb::Zero();
  double heap_width_ = 0, pending_width_ = 0;  // sums of Term::width
  std::vector<Term> heap_, pending_;
  std::vector<int> pool_, scratch_;  // blocker lists of the terms
  /// Two surfaces: every blocker opaque, and (with filters among the blockers) the opaque
  /// blockers alone, the filters left out: the two visible form factors bracket what passes.
  std::optional<BlockerSurface> surfaces_[2];
  std::vector<char> inserted_[2];
  std::unique_ptr<ExactGatherSession> session_;
};

LocalPassResult LocalPass::gather_by_clusters(const Vec3& x, const Vec3& n, double tolerance,
                                              const GatherScope& scope) const {
  return ClusterGather(*this, x, n, tolerance, scope).run();
}

}  // namespace rad
