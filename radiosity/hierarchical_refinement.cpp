#include <tbb/parallel_for.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "radiosity/hierarchical_state.h"
#include "radiosity/mesher.h"
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
  tbb::parallel_for(0, mesh.face_count(), [&](int f) {
    const int e = mesh.element(f);
    const Element& el = elements[e];
    if (buried_[e] || !(longest_edge(el.corners) > smallest)) return;
    const std::optional<Rgb> fitted = mesh.neighbour_plane_at(solution_, f);
    if (!fitted) return;
    const double miss = (el.radiosity - *fitted).cwiseAbs().maxCoeff();
    const Vec3& n = solution_.patches[el.patch].normal;
    const double length = longest_edge(el.corners);
    const bool near_contact = rays_.faces_within(el.centroid, n, length);
    const auto limit = [&](const Rgb& b) {
      return refinement_limit(settings_.refine_threshold, reference, b.maxCoeff(), near_contact);
    };
    split[f] = miss > limit(el.radiosity.cwiseMax(*fitted));
    if (split[f] || !near_contact || !(length > contact_size)) return;
    // Near a contact or a concave edge the local pass sees an element from close by, at a
    // large solid angle, and takes it as uniform: split it where its own links give any
    // corner a radiosity off its centre's by more than the limit (as the progressive solver
    // does during its shots), down to contact_size.
    const Rgb centre = own_gather(e, el.centroid, -1);
    for (int k = 0; k < static_cast<int>(el.corners.size()) && !split[f]; ++k) {
      const Rgb corner = own_gather(e, el.corners[k], k);
      const Rgb rho = reflectance(e) * row_scale_[e];
      const Rgb b_centre = el.radiosity,
                b_corner = el.radiosity + rho.cwiseProduct(corner - centre);
      split[f] = (b_corner - b_centre).cwiseAbs().maxCoeff() > limit(b_corner.cwiseMax(b_centre));
    }
  });
  std::vector<int> parents, children;
  // A patch one of whose leaves splits hands its patch links down: each of its leaves
  // measures them at its own centroid (an indirect shadow that its centroid's visibility
  // smeared over it is what the split is for). Its cluster links, far, stay shared.
  std::vector<int> handed;
  for (int f = 0; f < mesh.face_count(); ++f) {
    if (split[f] && !patch_links_[elements[mesh.element(f)].patch].empty())
      handed.push_back(elements[mesh.element(f)].patch);
  }
  std::sort(handed.begin(), handed.end());
  handed.erase(std::unique(handed.begin(), handed.end()), handed.end());
  std::vector<int> handed_leaves;
  for (const int p : handed) {
    for (const int e : patch_leaves_[p]) handed_leaves.push_back(e);
  }
  tbb::parallel_for(size_t(0), handed_leaves.size(), [&](size_t k) {
    const int e = handed_leaves[k];
    const Element& el = elements[e];
    const Patch& patch = solution_.patches[el.patch];
    for (const SourceLink& l : patch_links_[el.patch]) {
      const Rgb f = rays_.visible_form_factor(el.centroid, patch.normal, el.polygon,
                                              solution_.patches[l.source],
                                              stream_key(1, e, StreamKind::link, l.source));
      if (f != Rgb::Zero()) element_links_[e].push_back({-1 - l.source, f});
    }
  });
  for (const int e : handed_leaves) links_ += static_cast<long long>(element_links_[e].size());
  for (const int p : handed) {
    links_ -= static_cast<long long>(patch_links_[p].size());
    std::vector<SourceLink>().swap(patch_links_[p]);
    patch_row_[p] = cluster_row_[p];
  }
  for (const int e : handed_leaves) row_scale_[e] = scale_of(e);
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
  element_links_.resize(count);
  tbb::parallel_for(size_t(0), children.size(), [&](size_t k) {
    const int c = children[k];
    const Element& child = elements[c];
    const Patch& patch = solution_.patches[child.patch];
    buried_[c] = rays_.is_buried(child.centroid, patch.normal);
    radiosity_[c] = radiosity_[child.parent];
    if (buried_[c]) return;
    for (const SourceLink& l : element_links_[child.parent]) {
      const Rgb f = rays_.visible_form_factor(child.centroid, patch.normal, child.polygon,
                                              source_patch(l.source),
                                              stream_key(0, c, StreamKind::link, l.source));
      if (f != Rgb::Zero()) element_links_[c].push_back({l.source, f});
    }
    row_scale_[c] = scale_of(c);
  });
  for (const int e : parents) {
    links_ -= static_cast<long long>(element_links_[e].size());
    std::vector<SourceLink>().swap(element_links_[e]);
  }
  for (const int c : children) links_ += static_cast<long long>(element_links_[c].size());
  leaves_.clear();
  for (auto& list : patch_leaves_) list.clear();
  for (size_t e = 0; e < count; ++e) {
    if (!elements[e].is_leaf() || buried_[e]) continue;
    leaves_.push_back(static_cast<int>(e));
    patch_leaves_[elements[e].patch].push_back(static_cast<int>(e));
  }
  refined_ += static_cast<int>(parents.size());
  return static_cast<int>(parents.size());
}

/// What leaf e's own links (its sources near it) give at point x of it: x its centroid
/// (`corner` -1: the links' stored factors) or its corner `corner` (measured now).
Rgb HierarchicalSolver::own_gather(int e, const Vec3& x, int corner) const {
  const Element& el = solution_.elements[e];
  const Vec3& n = solution_.patches[el.patch].normal;
  Rgb h = Rgb::Zero();
  for (const SourceLink& l : element_links_[e]) {
    const Rgb f =
        corner < 0 ? l.factor
                   : rays_.visible_form_factor(x, n, el.polygon, source_patch(l.source),
                                               stream_key(corner, e, StreamKind::corner, l.source));
    h += f.cwiseProduct(source_radiosity(l.source));
  }
  return h;
}

}  // namespace rad
