#include "localpass/local_pass.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "geometry/lambert.h"
#include "hemisphere/blocker_surface.h"
#include "localpass/cluster_bounds.h"
#include "scene/polygon_faces.h"
#include "specular/mirror_images.h"
#include "specular/refraction_images.h"

namespace rad {
namespace {

/// A term of the sum with its certified interval, per channel: lo <= exact term <= hi.
struct Term {
  double width = 0;                          ///< max_c (hi - lo): the refinement order
  int index = -1;                            ///< Cluster (heap) or face (pending)
  int blockers_begin = 0, blockers_end = 0;  ///< Its blockers in the call's pool; none: seen whole
  Rgb lo = Rgb::Zero(), hi = Rgb::Zero();
  bool seen_whole() const { return blockers_begin == blockers_end; }
};
/// Widest first; ties by index, so that the order (and the image) does not depend on threads.
bool narrower(const Term& a, const Term& b) {
  return a.width != b.width ? a.width < b.width : a.index > b.index;
}

}  // namespace

std::vector<OctreeItem> octree_items(const std::vector<EmittingFace>& faces) {
  std::vector<OctreeItem> items;
  items.reserve(faces.size());
  for (const EmittingFace& f : faces) items.push_back({f.vertices, f.normal, f.exitance});
  return items;
}

struct LocalPass::Mirror {
  MirrorPiece first;                ///< The chain's first mirror: x must face it
  Eigen::AlignedBox3d sources;      ///< What can be seen through it (the culling beam's target)
  UnfoldedScene unfolded;           ///< The chain unfolded (specular/mirror_images.h)
  std::unique_ptr<LocalPass> pass;  ///< Over `unfolded`, which has no mirrors of its own
};

struct LocalPass::Refracting {
  Scene scene;  ///< A copy: the provenance and materials of each image
  std::vector<RefractingFacet> facets;
  std::vector<RefractionChain> chains;
  Method method;
  double tolerance;
  int max_pieces;
  bool culling;
  /// Per facet: the facets of its object when that object is convex (every vertex on or behind
  /// every facet's plane), else empty: x is inside a convex object only when it is behind all.
  std::vector<std::vector<int>> convex_object;
};

LocalPass::~LocalPass() = default;

LocalPass::LocalPass(const Scene& scene, std::vector<EmittingFace> faces, Method method,
                     const LocalPassSettings& settings)
    : faces_(std::move(faces)),
      tolerance_(scene.tolerance()),
      faces_by_query_(method == Method::hemisphere),
      occlusion_culling_(settings.occlusion_culling),
      octree_(octree_items(faces_), settings.octree),
      gatherer_(make_exact_gatherer(method, scene, faces_)),
      culling_(scene, faces_, octree_),
      clusters_(faces_) {
  filter_polygon_.resize(scene.polygons.size());
  for (size_t i = 0; i < scene.polygons.size(); ++i)
    filter_polygon_[i] = scene.materials[scene.polygons[i].material].is_filter();
  blocker_pieces_.resize(scene.polygons.size());
  for (EmittingFace& piece :
       faces_from_polygons(scene, std::vector<Rgb>(scene.polygons.size(), Rgb::Zero())))
    blocker_pieces_[piece.polygon].push_back(std::move(piece));
  in_plane_ = tolerance_.in_plane;
  if (static_cast<long>(scene.polygons.size()) >= settings.visible_set_from) {
    visible_set_ = std::make_unique<VisibleSet>(scene, blocker_pieces_);
    root_of_polygon_.assign(scene.polygons.size(), -1);
    for (const int root : clusters_.roots())
      root_of_polygon_[clusters_.clusters()[root].polygon] = root;
  }
  mirror_culling_ = settings.mirror_culling;
  if (!scene.lights.empty()) lights_ = std::make_unique<PointLightVisibility>(scene);
  if (settings.glossy_transfer) {
    auto glossy = std::make_unique<GlossyTransfer>(scene, settings.glossy);
    if (!glossy->empty()) glossy_ = std::move(glossy);
  }
  // Glossy surfaces are no plane mirrors to the local pass: their light comes by beams.
  std::vector<MirrorPiece> pieces = mirror_pieces(scene);
  std::erase_if(pieces, [&](const MirrorPiece& piece) {
    return scene.materials[scene.polygons[piece.polygon].material].is_glossy_mirror();
  });
  LocalPassSettings unfolded = settings;
  unfolded.mirror_depth = 0;         // an unfolded scene has no mirrors (images never reflect)
  unfolded.refraction_depth = 0;     // refraction is gathered at the real receiver only
  unfolded.glossy_transfer = false;  // nor glossy transfer
  // Unfolded scenes: the visibility culling is left off (its tests do not cover them).
  unfolded.visible_set_from = std::numeric_limits<int>::max();
  const int depth = settings.mirror_depth.value_or(scene.mirror_depth);
  for (const std::vector<int>& chain : mirror_chains(pieces, depth, in_plane_)) {
    auto m = std::make_unique<Mirror>();
    m->first = pieces[chain.front()];
    m->sources = sources_in_front(faces_, pieces, scene.lights, m->first, in_plane_);
    m->unfolded = unfold(scene, faces_, pieces, chain, in_plane_);
    m->pass = std::make_unique<LocalPass>(m->unfolded.scene, m->unfolded.faces, method, unfolded);
    mirrors_.push_back(std::move(m));
  }
  const int refraction_depth = settings.refraction_depth.value_or(scene.refraction_depth);
  if (refraction_depth > 0) {
    auto r = std::make_unique<Refracting>();
    r->facets = refracting_facets(scene);
    r->chains = refraction_chains(r->facets, refraction_depth, in_plane_);
    if (!r->chains.empty()) {
      r->scene = scene;
      r->method = method;
      r->tolerance = settings.refraction_tolerance;
      r->max_pieces = std::max(1, settings.refraction_max_pieces);
      r->culling = settings.refraction_culling;
      r->convex_object = convex_object_facets(r->facets, in_plane_);
      refracting_ = std::move(r);
    }
  }
}

void LocalPass::gather_refracted(const Refracting& r, const RefractionPath& path, const Vec3& x,
                                 const Vec3& n, LocalPassResult& result) const {
  for (const RefractedImage& image : refracted_images(r.scene, faces_, path, x, in_plane_)) {
    const auto gatherer = make_exact_gatherer(r.method, image.unfolded.scene, image.unfolded.faces);
    result.refracted += image.weight.cwiseProduct(exact_irradiance(*gatherer, x, n));
    ++result.refracted_images;
  }
}

void LocalPass::add_refracted(const Vec3& x, const Vec3& n, LocalPassResult& result) const {
  const Refracting& r = *refracting_;
  for (const RefractionChain& chain : r.chains) {
    // x on the side the chain starts from: in front of its first facet, or behind it.
    const double h = r.facets[chain.facets.front()].height(x);
    if (!(chain.from_inside ? h < -in_plane_ : h > in_plane_)) continue;
    if (chain.from_inside) {
      // Behind one facet of a convex object but in front of another: outside it, and every
      // line to the first facet's back crosses the object (nothing comes through).
      bool inside = true;
      for (const int f : r.convex_object[chain.facets.front()])
        inside = inside && r.facets[f].height(x) <= in_plane_;
      if (!inside) continue;
    }
    const int k = static_cast<int>(chain.facets.size());
    if (std::isfinite(r.tolerance)) {
      // The accuracy knob: the first facet in pieces, each the start of a traced path through
      // the chain's other facets, whole (RefractionPath::traced).
      RefractionPath path{{nullptr}, chain.from_inside, true};
      for (int j = 1; j < k; ++j) path.facets.push_back(&r.facets[chain.facets[j]]);
      const std::vector<const RefractingFacet*> beyond(path.facets.begin() + 1, path.facets.end());
      for (const RefractingFacet& piece :
           facet_pieces(r.facets[chain.facets.front()], x, !chain.from_inside, r.tolerance,
                        r.max_pieces, beyond)) {
        path.facets.front() = &piece;
        if (r.culling && !may_pass(path, x)) continue;
        gather_refracted(r, path, x, n, result);
      }
      continue;
    }
    // The paper's method: each facet whole, on the centroid path; a path whose images miss
    // each other is skipped (the beams, checked as the path grows).
    RefractionPath path{{}, chain.from_inside};
    bool passes = true;
    for (int j = 0; j < k && passes; ++j) {
      path.facets.push_back(&r.facets[chain.facets[j]]);
      passes = !r.culling || may_pass(path, x);
    }
    if (passes) gather_refracted(r, path, x, n, result);
  }
}

LocalPassResult LocalPass::gather(const Vec3& x, const Vec3& n, double tolerance) const {
  // The chains x reflects: it faces their first mirror, and (culling beams, 000 §5) x' sees
  // something through it that radiates or reflects: all light of a chain comes through its
  // first outline from what lies in front of it, so where x' sees none of that, the term is 0.
  std::vector<const Mirror*> active;
  for (const std::unique_ptr<Mirror>& m : mirrors_) {
    if (!(m->first.height(x) > in_plane_)) continue;  // the mirror's back, or edge-on
    if (mirror_culling_ && !may_see_through(m->first, m->first.reflect(x), m->sources)) continue;
    active.push_back(m.get());
  }
  // H is a sum of 1 + #active non-negative terms, each gathered to tolerance T / (1 + #active)
  // of its own brightest channel: the sum of the bounds is then at most T times the largest
  // of those, which is at most the brightest channel of H.
  const double share = tolerance / static_cast<double>(1 + active.size());
  // Point lights' direct light is exact (no width): part of the first term, whose stopping
  // rule then counts it in the value the bound is measured against.
  const Rgb from_lights =
      lights_ ? lights_->irradiance(x, n, culling_.candidates(x, n)) : Rgb::Zero();
  LocalPassResult result = gather_direct(x, n, share, from_lights);
  for (const Mirror* m : active) {
    const LocalPassResult r =
        m->pass->gather(m->unfolded.receiver(x), m->unfolded.receiver_normal(n), share);
    const Rgb& s = m->unfolded.specular;
    result.irradiance += s.cwiseProduct(r.irradiance);
    result.bound += s.cwiseProduct(r.bound);
    result.gathered_exactly += r.gathered_exactly;
    result.unoccluded += r.unoccluded;
    result.projected += r.projected;
    result.clusters += r.clusters;
    result.gathers += r.gathers;
    ++result.mirrored;
  }
  if (refracting_) add_refracted(x, n, result);
  if (glossy_) {
    const GlossyTransfer::Result g = glossy_->irradiance(x, n);
    result.glossy = g.irradiance;
    result.glossy_beams = g.beams;
  }
  return result;
}

LocalPassResult LocalPass::gather_direct(const Vec3& x, const Vec3& n, double tolerance,
                                         const Rgb& exact_part) const {
  if (occlusion_culling_) return gather_by_clusters(x, n, tolerance, exact_part);
  LocalPassResult result = gather_plainly(x, n);
  result.irradiance += exact_part;
  return result;
}

LocalPassResult LocalPass::gather_plainly(const Vec3& x, const Vec3& n) const {
  LocalPassResult result;
  const OcclusionSplit split = culling_.split_without_culling(x, n);
  if (split.shadowed.empty()) return result;
  std::vector<int> occluders;
  culling_.occluders(x, split.shadowed.front(), &occluders);
  const auto session = gatherer_->start(x, n);
  result.irradiance = session->step(split.shadowed.front().faces, occluders).irradiance;
  result.gathered_exactly = static_cast<int>(split.shadowed.front().faces.size());
  result.projected = session->projected();
  result.gathers = 1;
  return result;
}

LocalPassResult LocalPass::gather_by_clusters(const Vec3& x, const Vec3& n, double tolerance,
                                              const Rgb& exact_part) const {
  LocalPassResult result;
  const std::vector<Cluster>& clusters = clusters_.clusters();
  // What x may see (localpass/visible_set.h): the roots of the sum and the candidate blockers;
  // without the visibility culling, the whole scene.
  std::vector<int> seen;
  if (visible_set_) {
    seen = visible_set_->polygons(x, n);
    result.visible_polygons = static_cast<int>(seen.size());
  }
  const std::vector<int> candidates =
      visible_set_ ? culling_.candidates(x, n, seen) : culling_.candidates(x, n);
  const bool exact_only = !(tolerance > 0);

  // The sum H = exact + sum of heap terms + sum of pending terms + gathered, each in its interval.
  Rgb exact = exact_part;                            // faces seen whole: Lambert's formula
  Rgb heap_lo = Rgb::Zero(), heap_hi = Rgb::Zero();  // clusters not yet refined
  Rgb pending_hi = Rgb::Zero();                      // faces that may be hidden: [0, hi]
  Rgb gathered = Rgb::Zero();                        // the exact gather's total so far
  double heap_width = 0, pending_width = 0;          // sums of Term::width
  std::vector<Term> heap, pending;
  std::vector<int> pool, scratch;  // blocker lists of the terms
  // The hemisphere method: what may be hidden is resolved by exact visibility queries against
  // the blocking polygons, inserted as they are first named.
  const bool queries = !blocker_pieces_.empty();
  // Faces that may be hidden: by a query too (hemisphere), or by the method's own gather.
  const bool faces_by_query = queries && faces_by_query_;
  // Two surfaces: every blocker opaque, and (with filters among the blockers) the opaque
  // blockers alone, the filters left out: the two visible form factors bracket what passes.
  std::optional<BlockerSurface> surfaces[2];
  std::vector<char> inserted[2];
  const auto visible_form_factor = [&](const Cluster& cluster, int begin, int end,
                                       bool without_filters) {
    std::optional<BlockerSurface>& surface = surfaces[without_filters];
    std::vector<char>& in = inserted[without_filters];
    if (!surface) {
      surface.emplace(x, n, tolerance_);
      in.assign(blocker_pieces_.size(), 0);
    }
    for (int i = begin; i < end; ++i) {
      if (in[pool[i]]) continue;
      in[pool[i]] = 1;
      if (without_filters && filter_polygon_[pool[i]]) continue;
      for (const EmittingFace& piece : blocker_pieces_[pool[i]]) {
        surface->add(piece.polygon, piece.vertices, piece.normal);
        ++result.projected;
      }
    }
    ++result.projected;
    return surface->visible_form_factor(cluster.polygon, cluster.outline, cluster.normal);
  };

  // Adds cluster c, seen by x whole or through the blockers listed in pool[begin, end).
  const auto add = [&](int c, int begin, int end) {
    const Cluster& cluster = clusters[c];
    const double ff = point_polygon_form_factor(x, n, cluster.outline);
    if (!(ff > 0) || !(cluster.bmax.maxCoeff() > 0)) return;  // contributes nothing
    Term t{0, c, begin, end, Rgb::Zero(), cluster.bmax * ff};
    // What may be hidden, when queries are at hand: its visible form factor, exactly.
    // (At tolerance 0 a partly hidden cluster is only a way down to its faces: no query.)
    // Through filters, the visible form factor with them opaque (`visible`, for the lower
    // ends) and without them (`visible_hi`, for the upper ends): see the header. A face seen
    // through a filter is never exact by a query.
    const bool through_filter = std::any_of(pool.begin() + begin, pool.begin() + end,
                                            [&](int p) { return filter_polygon_[p] != 0; });
    const bool query = !t.seen_whole() && queries &&
                       (cluster.is_leaf() ? faces_by_query && !through_filter : !exact_only);
    // What is visible of the outline is part of it: a query above ff is rounding or a defect
    // of the visibility structure (issue 36 found one), and must not raise a lower end.
    const double visible =
        query ? std::min(ff, visible_form_factor(cluster, begin, end, false)) : ff;
    const double visible_hi = query && through_filter
                                  ? std::min(ff, visible_form_factor(cluster, begin, end, true))
                                  : visible;
    const bool known = t.seen_whole() || query;
    if (cluster.is_leaf() && known) {  // exact: B FF(x, visible part of the face)
      exact += faces_[cluster.face].exitance * visible;
      ++result.gathered_exactly;
      if (t.seen_whole()) ++result.unoccluded;
      return;
    }
    if (cluster.is_leaf()) {
      t.index = cluster.face;
      t.width = t.hi.maxCoeff();
      pending.push_back(t);
      std::push_heap(pending.begin(), pending.end(), narrower);
      pending_hi += t.hi, pending_width += t.width;
      return;
    }
    if (exact_only && t.seen_whole()) {  // every face will be summed: sum them now
      for (int i = 0; i < cluster.face_count; ++i) {
        const int f = clusters_.faces()[cluster.first_face + i];
        const double face_ff = point_polygon_form_factor(x, n, faces_[f].vertices);
        if (!(face_ff > 0) || !(faces_[f].exitance.maxCoeff() > 0)) continue;
        exact += faces_[f].exitance * face_ff;
        ++result.gathered_exactly, ++result.unoccluded;
      }
      return;
    }
    ++result.clusters;
    // Its faces' form factors sum to FF(x, their union) <= FF(x, outline) = ff; seen whole and
    // filling its outline, the sum is also >= ff minus what the gap can subtend.
    const double h = cluster.normal.dot(x - cluster.outline.front());
    const double ff_lo =
        known && cluster.fills_outline
            ? std::max(0.0, visible - cluster.gap_area / (std::numbers::pi * h * h))
            : 0.0;
    t.lo = cluster.bmin * ff_lo;  // zeroth order: bmin sum FF_A <= term <= bmax sum FF_A
    t.hi = cluster.bmax * visible_hi;
    // First order: with kmin <= k <= kmax on the outline (cluster_bounds.h), the term
    // sum B_A FF_A = bmean sum FF_A + sum (B_A - bmean) (FF_A - area_A kmid), since
    // sum (B_A - bmean) area_A = 0; each |FF_A - area_A kmid| <= area_A (kmax - kmin) / 2.
    const KernelBounds kernel = kernel_bounds(cluster, x, n, h);
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
    heap.push_back(t);
    std::push_heap(heap.begin(), heap.end(), narrower);
    heap_lo += t.lo, heap_hi += t.hi, heap_width += t.width;
  };
  // Cluster c under a parent whose blockers are pool[begin, end): its own are among them.
  const auto classify_and_add = [&](int c, int begin, int end) {
    if (begin == end) return add(c, begin, end);
    const Cluster& cluster = clusters[c];
    // A face under a partly hidden cluster: a query with the parent's blockers (a superset of
    // its own) is exact and costs about what the shafts would, so skip them.
    if (cluster.is_leaf() && faces_by_query) return add(c, begin, end);
    culling_.blockers(std::span<const int>(pool.data() + begin, pool.data() + end), x, cluster.box,
                      cluster.outline, cluster.polygon, &scratch);
    const int own = static_cast<int>(pool.size());
    pool.insert(pool.end(), scratch.begin(), scratch.end());
    add(c, own, static_cast<int>(pool.size()));
  };
  const auto add_root = [&](int root) {
    const Cluster& cluster = clusters[root];
    if (!culling_.in_front_of_polygon(cluster.polygon, x)) return;  // it cannot light x
    culling_.blockers(candidates, x, cluster.box, cluster.outline, cluster.polygon, &scratch);
    const int own = static_cast<int>(pool.size());
    pool.insert(pool.end(), scratch.begin(), scratch.end());
    add(root, own, static_cast<int>(pool.size()));
  };
  if (visible_set_) {
    for (const int p : seen)
      if (root_of_polygon_[p] >= 0) add_root(root_of_polygon_[p]);
  } else {
    for (const int root : clusters_.roots()) add_root(root);
  }

  const auto done = [&] {
    if (heap.empty() && pending.empty()) return true;
    if (exact_only) return false;
    const Rgb lo = exact + heap_lo + gathered, hi = exact + heap_hi + gathered + pending_hi;
    return 0.5 * (hi - lo).maxCoeff() <= tolerance * (0.5 * (hi + lo)).maxCoeff();
  };
  std::unique_ptr<ExactGatherSession> session;
  while (!done()) {
    if (!heap.empty() &&
        (exact_only || pending.empty() || heap.front().width >= pending.front().width)) {
      // Refine the widest cluster: its children's intervals replace its own.
      std::pop_heap(heap.begin(), heap.end(), narrower);
      const Term t = heap.back();
      heap.pop_back();
      heap_lo -= t.lo, heap_hi -= t.hi, heap_width -= t.width;
      for (const int child : clusters[t.index].children)
        classify_and_add(child, t.blockers_begin, t.blockers_end);
      continue;
    }
    // Gather the widest pending faces exactly, with whatever may hide them.
    double target = 0;  // what the pending widths may sum to after this step
    if (exact_only) {
      target = -1;  // all of them, in one step
    } else if (gatherer_->incremental()) {
      target = 0.5 * pending_width;  // small steps cost nothing extra: halve them
    } else {
      // Each step starts afresh: aim straight at the stopping rule, with what is known of H
      // (the whole width may be 2 T H / (1 - T); H is at least the lower end).
      const double h_lo = (exact + heap_lo + gathered).maxCoeff();
      target = std::max(0.0, 2 * tolerance * h_lo / std::max(1 - tolerance, 1e-12) - heap_width);
    }
    std::vector<OcclusionSplit::Group> groups;  // by polygon, for the occluder search
    std::vector<int> group_polygon, radiating;
    do {
      std::pop_heap(pending.begin(), pending.end(), narrower);
      const Term t = pending.back();
      pending.pop_back();
      pending_hi -= t.hi, pending_width -= t.width;
      radiating.push_back(t.index);
      const int polygon = faces_[t.index].polygon;
      const size_t g = std::ranges::find(group_polygon, polygon) - group_polygon.begin();
      if (g == group_polygon.size()) group_polygon.push_back(polygon), groups.emplace_back();
      OcclusionSplit::Group* group = &groups[g];
      group->faces.push_back(t.index);
      group->box.extend(bounding_box(faces_[t.index].vertices));
      group->blockers.insert(group->blockers.end(), pool.begin() + t.blockers_begin,
                             pool.begin() + t.blockers_end);
    } while (!pending.empty() && pending_width > target);
    if (pending.empty()) pending_hi = Rgb::Zero(), pending_width = 0;  // no rounding residue
    std::vector<int> occluders;
    for (OcclusionSplit::Group& group : groups) {
      std::ranges::sort(group.blockers);
      group.blockers.erase(std::unique(group.blockers.begin(), group.blockers.end()),
                           group.blockers.end());
      culling_.occluders(x, group, &occluders);
    }
    if (!session) session = gatherer_->start(x, n);
    gathered = session->step(radiating, occluders).irradiance;
    result.gathered_exactly += static_cast<int>(radiating.size());
    ++result.gathers;
  }
  if (session) result.projected += session->projected();

  // The interval of the sum, from the terms themselves (the running sums drift by rounding).
  Rgb lo = exact + gathered, hi = exact + gathered;
  for (const Term& t : heap) lo += t.lo, hi += t.hi;
  for (const Term& t : pending) hi += t.hi;
  result.bound = 0.5 * (hi - lo);
  result.irradiance = 0.5 * (hi + lo);
  return result;
}

}  // namespace rad
