#include "localpass/local_pass.h"

#include <algorithm>
#include <cmath>

#include "geometry/lambert.h"

namespace rad {
namespace {

/// FF(x, part of the face above the horizon): Lambert's formula, for a face nothing hides.
double unoccluded_form_factor(const EmittingFace& face, const Vec3& x, const Vec3& n) {
  return point_polygon_form_factor(x, n, face.vertices);
}

}  // namespace

std::vector<OctreeItem> octree_items(const std::vector<EmittingFace>& faces) {
  std::vector<OctreeItem> items;
  items.reserve(faces.size());
  for (const EmittingFace& f : faces) items.push_back({f.vertices, f.normal, f.exitance});
  return items;
}

LocalPass::LocalPass(const Scene& scene, std::vector<EmittingFace> faces, Method method,
                     const LocalPassSettings& settings)
    : faces_(std::move(faces)),
      occlusion_culling_(settings.occlusion_culling),
      octree_(octree_items(faces_), settings.octree),
      gatherer_(make_exact_gatherer(method, scene, faces_)),
      culling_(scene, faces_, octree_) {}

LocalPassResult LocalPass::gather(const Vec3& x, const Vec3& n, double tolerance) const {
  LocalPassResult result;
  const OcclusionSplit split =
      occlusion_culling_ ? culling_.split(x, n) : culling_.split_without_culling(x, n);

  // Faces nothing can hide: exact by Lambert's formula alone.
  Rgb unoccluded = Rgb::Zero();
  double unoccluded_covered = 0;
  for (const int f : split.unoccluded) {
    const double ff = unoccluded_form_factor(faces_[f], x, n);
    unoccluded += ff * faces_[f].exitance;
    unoccluded_covered += ff;
  }
  result.gathered_exactly = result.unoccluded = static_cast<int>(split.unoccluded.size());

  // The other faces by leaf, in order of decreasing bound: the sum of their unoccluded terms.
  struct Entry {
    double key;
    int group;
    Rgb bound, bmax;
  };
  std::vector<Entry> entries;
  for (size_t g = 0; g < split.shadowed.size(); ++g) {
    Rgb bound = Rgb::Zero(), bmax = Rgb::Zero();
    for (const int f : split.shadowed[g].faces) {
      bound += unoccluded_form_factor(faces_[f], x, n) * faces_[f].exitance;
      bmax = bmax.cwiseMax(faces_[f].exitance);
    }
    if (bound.maxCoeff() > 0)
      entries.push_back({bound.maxCoeff(), static_cast<int>(g), bound, bmax});
  }
  std::sort(entries.begin(), entries.end(), [&](const Entry& a, const Entry& b) {
    return a.key != b.key ? a.key > b.key
                          : split.shadowed[a.group].leaf < split.shadowed[b.group].leaf;
  });
  // From entry i on: the sum of the bounds and the largest radiosity.
  std::vector<Rgb> bound_sum(entries.size() + 1, Rgb::Zero()),
      bmax_max(entries.size() + 1, Rgb::Zero());
  for (size_t i = entries.size(); i-- > 0;) {
    bound_sum[i] = bound_sum[i + 1] + entries[i].bound;
    bmax_max[i] = bmax_max[i + 1].cwiseMax(entries[i].bmax);
  }

  Rgb exact = unoccluded;
  double covered = unoccluded_covered;  // form factor covered by visible parts gathered exactly
  size_t next = 0;
  // What the unselected faces can still add, certified (see the header).
  const bool knows_coverage = gatherer_->reports_coverage();
  const auto remainder = [&] {
    Rgb r = bound_sum[next];
    if (knows_coverage) r = r.cwiseMin(bmax_max[next] * std::max(0.0, 1 - covered));
    return r;
  };
  const auto done = [&] {
    if (next == entries.size()) return true;
    if (!(tolerance > 0)) return false;
    const Rgb half = 0.5 * remainder();
    return half.maxCoeff() <= tolerance * (exact + half).maxCoeff();
  };
  std::unique_ptr<ExactGatherSession> session;
  if (!entries.empty()) session = gatherer_->start(x, n);
  while (!done()) {
    // Choose the next batch of leaf groups.
    std::vector<int> batch;
    if (!(tolerance > 0)) {
      while (next < entries.size()) batch.push_back(entries[next++].group);
    } else if (gatherer_->incremental()) {
      // Projection is incremental, so batches may be small: enough to halve the bound sum.
      const double target = 0.5 * bound_sum[next].maxCoeff();
      do {
        batch.push_back(entries[next++].group);
      } while (next < entries.size() && bound_sum[next].maxCoeff() > target);
    } else {
      // Each step starts afresh: aim straight at the stopping rule with what is known of H,
      // R <= 2 T H / (1 - T) (before the first step, H is at least the unoccluded part).
      const double target = 2 * tolerance * exact.maxCoeff() / std::max(1 - tolerance, 1e-12);
      do {
        batch.push_back(entries[next++].group);
      } while (next < entries.size() && bound_sum[next].maxCoeff() > target);
    }
    // Gather the batch's faces exactly, with whatever may hide them.
    std::vector<int> radiating, occluders;
    for (const int g : batch) {
      const OcclusionSplit::Group& group = split.shadowed[g];
      radiating.insert(radiating.end(), group.faces.begin(), group.faces.end());
      culling_.occluders(x, group, &occluders);
    }
    result.gathered_exactly += static_cast<int>(radiating.size());
    result.voxels += static_cast<int>(batch.size());
    ++result.gathers;
    const ExactGatherTotal total = session->step(radiating, occluders);
    exact = unoccluded + total.irradiance;
    if (total.covered) covered = unoccluded_covered + *total.covered;
  }
  if (session) result.projected = session->projected();
  result.bound = 0.5 * remainder();
  result.irradiance = exact + result.bound;
  return result;
}

}  // namespace rad
