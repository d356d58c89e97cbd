#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "radiosity/hierarchical_state.h"
#include "radiosity/random_stream.h"
#include "radiosity/solver.h"

namespace rad {

void HierarchicalSolver::link_patch(int p) {
  if (patch_leaves_[p].empty() || clusters_->empty()) return;
  std::vector<int> stack{0};
  Blockers blockers = enclosing(p);
  link_from(p, stack, blockers);
  settle(p);
}

void HierarchicalSolver::link_from(int p, std::vector<int>& stack, Blockers& blockers) {
  const Vec3& x = centroid_[p];
  while (!stack.empty()) {
    const int index = stack.back();
    stack.pop_back();
    const PatchCluster& c = (*clusters_)[index];
    if (!(highest_above(c.box, p) > in_plane_)) continue;
    const double distance = std::sqrt(c.box.squaredExteriorDistance(x)) - radius_[p];
    if (distance > 0) {  // (a box that meets p's bounding sphere is not worth the test)
      std::array<Vec3, 8> corners;
      for (int k = 0; k < 8; ++k) corners[k] = c.box.corner(Eigen::AlignedBox3d::CornerType(k));
      if (hidden_whole(corners, c.box, blockers)) continue;
    }
    if (small_beside(c.size, distance) && link_cluster(p, index)) continue;
    if (!defer(p, index)) open(p, index, stack, blockers);
  }
}

HierarchicalSolver::Blockers HierarchicalSolver::enclosing(int p) const {
  Blockers blockers;
  // The points of p that will ever gather through its links: its leaves' centroids, or, where
  // refinement may split them, anywhere on it (the hull of its corners).
  if (keep_blocked_) {
    blockers.from = solution_.patches[p].corners;
  } else {
    for (const int e : patch_leaves_[p]) blockers.from.push_back(solution_.elements[e].centroid);
  }
  if (blockers.from.empty()) return blockers;
  for (int k = 0; k < 27; ++k) {  // the 26 directions to a cube's corners, edges and faces
    const Vec3 d(k % 3 - 1, k / 3 % 3 - 1, k / 9 - 1);
    if (k == 13) continue;  // (its centre)
    const std::optional<Hit> hit = caster_.closest_hit({centroid_[p], d.normalized()}, epsilon_);
    if (!hit || hit->polygon == solution_.patches[p].polygon) continue;
    std::vector<Blocker>& found = blockers.polygons;
    if (std::any_of(found.begin(), found.end(),
                    [&](const Blocker& b) { return b.polygon == hit->polygon; }))
      continue;
    // Its plane turned so that p's gathering points lie in front.
    const Polygon& polygon = scene_.polygons[hit->polygon];
    const double sign = polygon.normal.dot(blockers.from[0] - polygon.vertices[0]) > 0 ? 1 : -1;
    found.push_back(
        {hit->polygon, sign * polygon.normal, sign * polygon.normal.dot(polygon.vertices[0])});
  }
  return blockers;
}

bool HierarchicalSolver::hidden_whole(std::span<const Vec3> to, const Eigen::AlignedBox3d& box,
                                      Blockers& blockers) const {
  std::vector<Blocker>& polygons = blockers.polygons;
  const Vec3 centre = box.center();
  const Vec3 half = box.sizes() / 2;
  for (auto b = polygons.begin(); b != polygons.end(); ++b) {
    // A quick look first: the box's highest point over the blocker's plane must lie behind it
    // (for a cluster, what Shooter::hides_between asks of its corners; for a patch, a little
    // more).
    if (!(b->normal.dot(centre) + b->normal.cwiseAbs().dot(half) - b->offset < -epsilon_)) continue;
    if (!rays_.hides_between(blockers.from, to, b->polygon)) continue;
    std::rotate(polygons.begin(), b, b + 1);  // the last that hid something first
    return true;
  }
  return false;
}

void HierarchicalSolver::open(int p, int entry, std::vector<int>& stack, Blockers& blockers) {
  if (entry < 0) {
    link_patches(p, -1 - entry);
    return;
  }
  const PatchCluster& c = (*clusters_)[entry];
  if (c.left >= 0) {
    stack.push_back(c.left + 1);
    stack.push_back(c.left);
    return;
  }
  for (int k = c.first; k < c.first + c.count; ++k) {
    const int q = clusters_->patch(k);
    if (!may_see(p, q)) continue;
    const std::vector<Vec3>& corners = solution_.patches[q].corners;
    Eigen::AlignedBox3d box;
    for (const Vec3& corner : corners) box.extend(corner);
    if (!hidden_whole(corners, box, blockers) && !defer(p, -1 - q)) link_patches(p, q);
  }
}

double HierarchicalSolver::reach(int p, int entry) const {
  Sphere source;
  const Rgb* brightest;
  if (entry >= 0) {
    const PatchCluster& c = (*clusters_)[entry];
    source = {c.box.center(), c.size / 2};
    brightest = &cluster_brightest_[entry];
  } else {
    source = {centroid_[-1 - entry], radius_[-1 - entry]};
    brightest = &patch_brightest_[-1 - entry];
  }
  const Sphere receiver{centroid_[p], radius_[p]};
  return sphere_form_factor_bound(receiver, solution_.patches[p].normal, source) *
         brightest->maxCoeff();
}

bool HierarchicalSolver::defer(int p, int entry) {
  if (!(reach(p, entry) <= defer_budget_ / kDeferredPieces) || defer_budget_ == 0) return false;
  deferred_[p].push_back(entry);
  return true;
}

int HierarchicalSolver::settle(int p) {
  std::vector<int>& deferred = deferred_[p];
  // A heap of (reach, entry): the brightest on top, ties by entry (the same for any thread
  // count).
  std::vector<std::pair<double, int>> heap;
  double total = 0;
  const auto take = [&] {
    for (const int entry : deferred) {
      heap.emplace_back(reach(p, entry), entry);
      total += heap.back().first;
      std::push_heap(heap.begin(), heap.end());
    }
    deferred.clear();
  };
  take();
  if (total <= defer_budget_) {
    for (const auto& [brings, entry] : heap) deferred.push_back(entry);
    return 0;
  }
  int opened = 0;
  std::vector<int> stack;
  // (No blockers here: asking rays for them again at each opening round took the IFC house's
  // coarse solve from 34.6 s to 41.9 s, and the building's time did not change.)
  Blockers blockers;
  while (total > defer_budget_ && !heap.empty()) {
    std::pop_heap(heap.begin(), heap.end());
    const auto [brings, entry] = heap.back();
    heap.pop_back();
    total -= brings;
    ++opened;
    open(p, entry, stack, blockers);
    link_from(p, stack, blockers);
    take();  // what the opening left out in turn
  }
  for (const auto& [brings, entry] : heap) deferred.push_back(entry);
  return opened;
}

void HierarchicalSolver::find_brightest(const std::vector<Rgb>& radiosity) {
  patch_brightest_.assign(solution_.patches.size(), Rgb::Zero());
  for (size_t p = 0; p < patch_leaves_.size(); ++p) {
    for (const int e : patch_leaves_[p])
      patch_brightest_[p] = patch_brightest_[p].cwiseMax(radiosity[e]);
  }
  cluster_brightest_.assign(clusters_->size(), Rgb::Zero());
  for (int i = clusters_->size(); i-- > 0;) {  // children after their parents
    const PatchCluster& c = (*clusters_)[i];
    Rgb& b = cluster_brightest_[i];
    if (c.left >= 0) {
      b = cluster_brightest_[c.left].cwiseMax(cluster_brightest_[c.left + 1]);
      continue;
    }
    for (int k = c.first; k < c.first + c.count; ++k)
      b = b.cwiseMax(patch_brightest_[clusters_->patch(k)]);
  }
}

int HierarchicalSolver::open_deferred() {
  find_brightest(radiosity_);
  const size_t count = solution_.patches.size();
  std::vector<int> opened(count, 0);
  for_in_parts(count, 0, 1, reporter(SolveProgress::Stage::opening),
               [&](size_t p) { opened[p] = settle(static_cast<int>(p)); });
  std::vector<int> changed, handed;
  for (size_t p = 0; p < count; ++p) {
    if (opened[p] == 0) continue;
    changed.push_back(static_cast<int>(p));
    if (handed_[p]) handed.push_back(static_cast<int>(p));
  }
  if (changed.empty()) return 0;
  hand_down(handed);
  for (const int p : changed) patch_row_[p] = patch_row(p);
  std::vector<int> leaves;
  for (const int p : changed)
    leaves.insert(leaves.end(), patch_leaves_[p].begin(), patch_leaves_[p].end());
  tbb::parallel_for(size_t(0), leaves.size(),
                    [&](size_t k) { row_scale_[leaves[k]] = scale_of(leaves[k]); });
  count_links();
  int total = 0;
  for (const int n : opened) total += n;
  return total;
}

bool HierarchicalSolver::link_cluster(int p, int index) {
  const PatchCluster& c = (*clusters_)[index];
  const Vec3& x = centroid_[p];
  const Vec3 n = solution_.patches[p].normal;
  Vec3 w = x - c.centre;
  const double r = w.norm();
  if (!(r > 0)) return false;
  w /= r;
  // The picks of the bins turned to the receiver, the bin it faces most first, in turn.
  const std::array<double, kBins> toward = bin_weights(w);
  std::array<int, kBins> bins_order{0, 1, 2, 3, 4, 5};
  std::stable_sort(bins_order.begin(), bins_order.end(),
                   [&](int a, int b) { return toward[a] > toward[b]; });
  std::array<int, kClusterRays> samples;
  int rays = 0;
  for (int k = 0; k < kClusterRays && rays < kClusterRays; ++k) {
    for (const int b : bins_order) {
      if (!(toward[b] > 0) || rays == kClusterRays) continue;
      const int q = c.turned[b][k];
      if (q >= 0 && std::find(samples.begin(), samples.begin() + rays, q) == samples.begin() + rays)
        samples[rays++] = q;
    }
  }
  if (rays == 0) return true;  // no patch of it is turned to the receiver: no link
  int passed = 0;
  for (int k = 0; k < rays; ++k) {
    const int q = samples[k];
    const Vec3 d = centroid_[q] - x;
    const double length = d.norm();
    if (!(length > 2 * epsilon_)) {
      ++passed;
      continue;
    }
    passed += !caster_.occluded({x, d / length}, epsilon_, length - epsilon_);
  }
  if (passed != 0 && passed != rays) return false;
  if (passed == 0) return true;  // nothing arrives: no link
  const ClusterLink link{index, cluster_weights(index, x, n)};
  if (std::all_of(link.weight.begin(), link.weight.end(), [](float v) { return v == 0; }))
    return true;  // behind the receiver
  cluster_links_[p].push_back(link);
  return true;
}

void HierarchicalSolver::link_patches(int p, int q) {
  if (!may_see(p, q)) return;
  const Patch& rp = solution_.patches[p];
  const Patch& sq = solution_.patches[q];
  const double distance = (centroid_[q] - centroid_[p]).norm() - radius_[p] - radius_[q];
  if (small_beside(2 * std::max(radius_[p], radius_[q]), distance)) {
    const Rgb f = rays_.visible_form_factor(centroid_[p], rp.normal, rp.polygon, sq,
                                            stream_key(0, p, StreamKind::link, q));
    if (f != Rgb::Zero()) {
      patch_links_[p].push_back({q, f});
    } else if (keep_blocked_) {
      patch_blocked_[p].push_back(q);
    }
    return;
  }
  for (const int e : patch_leaves_[p]) {
    const Element& el = solution_.elements[e];
    // Past q's near field, e takes q whole: its exact form factor at e's centroid, at q's
    // mean radiosity.
    const bool whole = !in_source_near_field(el.centroid, {centroid_[q], radius_[q]});
    const std::vector<int> one{-1 - q};
    for (const int s : whole ? one : patch_leaves_[q]) {
      const Rgb f = rays_.visible_form_factor(el.centroid, rp.normal, el.polygon, source_patch(s),
                                              stream_key(0, e, StreamKind::link, s));
      if (f != Rgb::Zero()) {
        element_links_[e].push_back({s, f});
      } else if (keep_blocked_) {
        element_blocked_[e].push_back(s);
      }
    }
  }
}

}  // namespace rad
