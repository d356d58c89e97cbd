#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <vector>

#include "radiosity/hierarchical_state.h"
#include "radiosity/mesher.h"
#include "radiosity/near_field.h"
#include "radiosity/patch_mesh.h"
#include "radiosity/random_stream.h"
#include "radiosity/refinement_limit.h"

namespace rad {

/// Splits the leaves whose radiosity misses the plane through their mesh neighbours' by
/// more than the refinement limit (the progressive solver's refine_by_neighbours: Gouraud
/// display and the local pass take a plane well, not what it misses: shadow edges, corners).
/// Each new leaf takes its parent's radiosity and patch links, and measures its own links
/// to the sources its parent linked to element by element. Returns the number split.
int HierarchicalSolver::refine() {
  const double reference = reference_radiosity(scene_);
  if (!(settings_.refine_threshold > 0 && reference > 0)) return 0;
  std::vector<Element>& elements = solution_.elements;
  for (const int e : leaves_) elements[e].radiosity = radiosity_[e];
  const ElementMesh mesh(solution_, scene_.tolerance().pad);
  const double smallest = settings_.min_element_size * diagonal_;
  const double contact_size = std::max(smallest, settings_.patch_size * diagonal_ / 16);
  std::vector<char> split(mesh.face_count(), 0);
  faint_dropped_.resize(elements.size(), 0);
  const std::function<void(double)> refining = reporter(SolveProgress::Stage::refining);
  for_in_parts(static_cast<size_t>(mesh.face_count()), 0, 0.5, refining, [&](size_t face) {
    const int f = static_cast<int>(face);
    const int e = mesh.element(f);
    const Element& el = elements[e];
    if (buried_[e] || !(longest_edge(el.corners) > smallest)) return;
    // A corner element of a polygon can have fewer than three mesh neighbours (then no plane),
    // and the contact test below is what it needs most.
    const std::optional<Rgb> fitted = mesh.neighbour_plane_at(solution_, f);
    const Vec3& n = solution_.patches[el.patch].normal;
    const double length = longest_edge(el.corners);
    const bool near_contact = rays_.faces_within(el.centroid, n, length);
    const auto limit = [&](const Rgb& b) {
      return refinement_limit(settings_.refine_threshold, reference, b.maxCoeff(), near_contact);
    };
    split[f] = fitted && (el.radiosity - *fitted).cwiseAbs().maxCoeff() >
                             limit(el.radiosity.cwiseMax(*fitted));
    if (split[f] || !near_contact || !(length > contact_size)) return;
    // Near a contact or a concave edge the local pass sees an element from close by, at a
    // large solid angle, and takes it as uniform: split it where its own links give any
    // corner a radiosity off its centre's by more than the limit (as the progressive solver
    // does during its shots), down to contact_size.
    drop_faint_hidden(e, reference);
    const Rgb centre = own_gather(e, el.centroid, -1);
    for (int k = 0; k < static_cast<int>(el.corners.size()) && !split[f]; ++k) {
      const Rgb corner = own_gather(e, el.corners[k], k);
      const Rgb rho = reflectance(e) * row_scale_[e];
      const Rgb lit = lights_at(e, el.corners[k]) - direct_[e];
      const Rgb b_centre = el.radiosity, b_corner = el.radiosity +
                                                    rho.cwiseProduct(corner - centre) +
                                                    reflectance(e).cwiseProduct(lit);
      split[f] = (b_corner - b_centre).cwiseAbs().maxCoeff() > limit(b_corner.cwiseMax(b_centre));
    }
  });
  std::vector<int> parents, children;
  // A patch one of whose leaves splits hands its links down: each of its leaves measures its
  // patch links at its own centroid (an indirect shadow that its centroid's visibility smeared
  // over it is what the split is for) and weighs its cluster links there (a leaf at a junction
  // sees the far parts of the surface it meets edge-on, its patch's centroid did not).
  std::vector<int> handed;
  for (int f = 0; f < mesh.face_count(); ++f) {
    const int p = elements[mesh.element(f)].patch;
    if (split[f] &&
        !(patch_links_[p].empty() && cluster_links_[p].empty() && patch_blocked_[p].empty()))
      handed.push_back(p);
  }
  std::sort(handed.begin(), handed.end());
  handed.erase(std::unique(handed.begin(), handed.end()), handed.end());
  hand_down(handed);
  for (int f = 0; f < mesh.face_count(); ++f) {
    if (!split[f]) continue;
    const int e = mesh.element(f);
    parents.push_back(e);
    split_element(elements, e);
    for (int c = elements[e].first_child; c < elements[e].first_child + 4; ++c)
      children.push_back(c);
  }
  if (parents.empty()) return 0;
  const size_t count = elements.size();
  buried_.resize(count, 0);
  radiosity_.resize(count, Rgb::Zero());
  row_scale_.resize(count, 1.0);
  direct_.resize(count, Rgb::Zero());
  element_links_.resize(count);
  element_cluster_links_.resize(count);
  element_blocked_.resize(count);
  faint_dropped_.resize(count, 0);
  tbb::parallel_for(size_t(0), parents.size(),
                    [&](size_t k) { drop_faint_hidden(parents[k], reference); });
  for_in_parts(children.size(), 0.5, 1, refining, [&](size_t k) {
    const int c = children[k];
    const Element& child = elements[c];
    const Patch& patch = solution_.patches[child.patch];
    buried_[c] = rays_.is_buried(child.centroid, patch.normal);
    radiosity_[c] = radiosity_[child.parent];
    if (buried_[c]) return;
    light(c);
    for (const SourceLink& l : element_links_[child.parent])
      link_or_hide(c, l.source, stream_key(0, c, StreamKind::link, l.source));
    for (const int s : element_blocked_[child.parent])
      link_or_hide(c, s, stream_key(0, c, StreamKind::link, s));
    for (const ClusterLink& l : element_cluster_links_[child.parent]) {
      element_cluster_links_[c].push_back(
          {l.cluster, cluster_weights(l.cluster, child.centroid, patch.normal)});
    }
    row_scale_[c] = scale_of(c);
  });
  for (const int e : parents) {
    std::vector<SourceLink>().swap(element_links_[e]);
    std::vector<ClusterLink>().swap(element_cluster_links_[e]);
    std::vector<int>().swap(element_blocked_[e]);
  }
  leaves_.clear();
  for (auto& list : patch_leaves_) list.clear();
  for (size_t e = 0; e < count; ++e) {
    if (!elements[e].is_leaf() || buried_[e]) continue;
    leaves_.push_back(static_cast<int>(e));
    patch_leaves_[elements[e].patch].push_back(static_cast<int>(e));
  }
  refined_ += static_cast<int>(parents.size());
  open_sources();
  return static_cast<int>(parents.size());
}

void HierarchicalSolver::hand_down(const std::vector<int>& handed) {
  const std::vector<Element>& elements = solution_.elements;
  std::vector<int> handed_leaves;
  for (const int p : handed) {
    for (const int e : patch_leaves_[p]) handed_leaves.push_back(e);
  }
  tbb::parallel_for(size_t(0), handed_leaves.size(), [&](size_t k) {
    const int e = handed_leaves[k];
    const Element& el = elements[e];
    const Patch& patch = solution_.patches[el.patch];
    for (const SourceLink& l : patch_links_[el.patch])
      link_or_hide(e, -1 - l.source, stream_key(1, e, StreamKind::link, l.source));
    for (const int q : patch_blocked_[el.patch])
      link_or_hide(e, -1 - q, stream_key(1, e, StreamKind::link, q));
    for (const ClusterLink& l : cluster_links_[el.patch])
      element_cluster_links_[e].push_back(
          {l.cluster, cluster_weights(l.cluster, el.centroid, patch.normal)});
  });
  for (const int p : handed) {
    handed_[p] = 1;
    std::vector<SourceLink>().swap(patch_links_[p]);
    std::vector<ClusterLink>().swap(cluster_links_[p]);
    std::vector<int>().swap(patch_blocked_[p]);
    patch_row_[p] = Rgb::Zero();
  }
  for (const int e : handed_leaves) row_scale_[e] = scale_of(e);
}

void HierarchicalSolver::open_sources() {
  const std::vector<Element>& elements = solution_.elements;
  tbb::parallel_for(size_t(0), leaves_.size(), [&](size_t k) {
    const int e = leaves_[k];
    std::vector<SourceLink>& links = element_links_[e];
    if (std::none_of(links.begin(), links.end(), [&](const SourceLink& l) {
          return l.source < 0 || !elements[l.source].is_leaf();
        }))
      return;
    std::vector<SourceLink> out;
    out.reserve(links.size());
    bool opened = false;
    for (const SourceLink& l : links) opened |= link_down(e, l, out);
    if (!opened) return;
    links.swap(out);
    row_scale_[e] = scale_of(e);
  });
  count_links();
}

/// Appends to `out` leaf e's link to the source of `link`, or, where that source has pieces
/// (a split element's children, a patch's top-level elements) and is not small beside its
/// distance from e's centroid (link_patches' opening test), its links to the pieces, in turn
/// (pieces it does not see go to its blocked sources). True when it opened the source.
bool HierarchicalSolver::link_down(int e, const SourceLink& link, std::vector<SourceLink>& out) {
  const std::vector<Element>& elements = solution_.elements;
  const Element& el = elements[e];
  const int s = link.source;
  std::vector<int> pieces;
  if (s < 0) {
    pieces = patch_roots_[-1 - s];
  } else if (!elements[s].is_leaf()) {
    for (int c = elements[s].first_child; c < elements[s].first_child + 4; ++c) pieces.push_back(c);
  }
  if (!pieces.empty()) {
    const Vec3& centre = s < 0 ? centroid_[-1 - s] : elements[s].centroid;
    const double radius =
        s < 0 ? radius_[-1 - s] : bounding_sphere(elements[s].corners, centre).radius;
    const double area = s < 0 ? solution_.patches[-1 - s].area : elements[s].area;
    if (!needs_pieces(e, {centre, radius}, area, pieces)) pieces.clear();
  }
  if (pieces.empty()) {
    out.push_back(link);
    return false;
  }
  const Vec3& n = solution_.patches[el.patch].normal;
  for (const int c : pieces) {
    if (buried_[c] && elements[c].is_leaf()) continue;
    const Rgb f =
        rays_.visible_form_factor(el.centroid, n, el.polygon, solution_.element_as_patch(c),
                                  stream_key(0, e, StreamKind::link, c));
    if (f != Rgb::Zero()) {
      link_down(e, {c, f}, out);
    } else {
      element_blocked_[e].push_back(c);
    }
  }
  return true;
}

bool HierarchicalSolver::needs_pieces(int e, const Sphere& source, double area,
                                      const std::vector<int>& pieces) const {
  const Element& el = solution_.elements[e];
  if (in_source_near_field(el.centroid, source)) return true;
  const double rho = reflectance(e).maxCoeff();
  if (!(rho > 0)) return false;
  Rgb least = Rgb::Constant(std::numeric_limits<double>::infinity()), largest = -least;
  for (const int c : pieces) {
    const bool dead = solution_.elements[c].is_leaf()
                          ? buried_[c] != 0
                          : c < static_cast<int>(live_below_.size()) && live_below_[c] == 0;
    if (dead) continue;  // (its radiosity is no light's)
    least = least.cwiseMin(radiosity_[c]);
    largest = largest.cwiseMax(radiosity_[c]);
  }
  const double spread = (largest - least).maxCoeff();
  // (The smallest limit e could have: the one near a contact.)
  const double tolerated =
      NearField::limit_share *
      refinement_limit(settings_.refine_threshold, reference_, radiosity_[e].maxCoeff(), true) /
      rho;
  return NearField::needs_pieces(el.centroid, source, area, spread, tolerated);
}

void HierarchicalSolver::drop_faint_hidden(int e, double reference) {
  std::vector<int>& hidden = element_blocked_[e];
  if (faint_dropped_[e] || hidden.empty()) return;
  faint_dropped_[e] = 1;
  const Element& el = solution_.elements[e];
  const Vec3& n = solution_.patches[el.patch].normal;
  const double rho = reflectance(e).maxCoeff();
  // The limit is the smallest the refinement could take for e (the near-contact one).
  const double budget = kFaintHidden * refinement_limit(settings_.refine_threshold, reference,
                                                        radiosity_[e].maxCoeff(), true);
  std::vector<std::pair<double, int>> reach;  // what each would bring e if seen whole
  reach.reserve(hidden.size());
  for (const int s : hidden) {
    const Patch source = source_patch(s);
    const double f = unblocked_form_factor(el.centroid, n, source.corners, source.normal);
    reach.emplace_back(rho * std::max(0.0, f) * source_radiosity(s).maxCoeff(), s);
  }
  std::sort(reach.begin(), reach.end());  // (by reach, then index: the same for any thread)
  double dropped = 0;
  hidden.clear();
  for (const auto& [brings, s] : reach) {
    if (dropped + brings <= budget) {
      dropped += brings;
    } else {
      hidden.push_back(s);
    }
  }
}

/// Measures leaf e's link to `source` (as element links name it) at e's centroid: a link where
/// any of it is seen, else a hidden source.
void HierarchicalSolver::link_or_hide(int e, int source, uint64_t key) {
  const Element& el = solution_.elements[e];
  const Rgb f = rays_.visible_form_factor(el.centroid, solution_.patches[el.patch].normal,
                                          el.polygon, source_patch(source), key);
  if (f != Rgb::Zero()) {
    element_links_[e].push_back({source, f});
  } else {
    element_blocked_[e].push_back(source);
  }
}

Rgb HierarchicalSolver::own_gather(int e, const Vec3& x, int corner) const {
  const Element& el = solution_.elements[e];
  const Vec3& n = solution_.patches[el.patch].normal;
  Rgb h = Rgb::Zero();
  for (const SourceLink& l : element_links_[e]) {
    const Rgb f =
        corner < 0 ? Rgb::Constant(l.factor)
                   : rays_.visible_form_factor(x, n, el.polygon, source_patch(l.source),
                                               stream_key(corner, e, StreamKind::corner, l.source));
    h += f.cwiseProduct(source_radiosity(l.source));
  }
  for (const ClusterLink& l : element_cluster_links_[e]) {
    h += taken(corner < 0 ? l : ClusterLink{l.cluster, cluster_weights(l.cluster, x, n)},
               clusters_->flux(l.cluster));
  }
  if (corner < 0) return h;  // the blocked sources give nothing at the centroid
  for (const int s : element_blocked_[e]) {
    const Rgb f = rays_.visible_form_factor(x, n, el.polygon, source_patch(s),
                                            stream_key(corner, e, StreamKind::corner, s));
    h += f.cwiseProduct(source_radiosity(s));
  }
  return h;
}

}  // namespace rad
