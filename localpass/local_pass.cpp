#include "localpass/local_pass.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/polygon_faces.h"
#include "specular/mirror_images.h"
#include "specular/refraction_images.h"

namespace rad {

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
      tile_(settings.tile),
      tile_when_it_pays_(settings.tile_when_it_pays),
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
  if (occlusion_culling_) {
    return gather_by_clusters(x, n, tolerance,
                              GatherScope{.known_lo = exact_part, .known_hi = exact_part});
  }
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

}  // namespace rad
