#include "localpass/local_pass.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rad {
namespace {

/// The cone of directions from x that a sphere fills, and its depth range.
struct Cone {
  Vec3 axis = Vec3::UnitZ();
  double cos_half = -1, sin_half = 0;  ///< Of the half angle; cos -1: x inside (every direction)
  double nearest = 0, farthest = 0;
};

Cone cone_of(const Vec3& x, const Vec3& centre, double radius) {
  Cone cone;
  const Vec3 d = centre - x;
  const double distance = d.norm();
  cone.farthest = distance + radius;
  if (distance <= radius) return cone;
  cone.axis = d / distance;
  cone.sin_half = radius / distance;
  cone.cos_half = std::sqrt(1 - cone.sin_half * cone.sin_half);
  cone.nearest = distance - radius;
  return cone;
}

/// Whether something inside cone `a` may hide something inside cone `b` from x: a reaches
/// nearer than b's far end and the cones overlap, i.e. the angle between the axes is at most
/// the sum of the half angles. Conservative (spheres around boxes; a little slack).
bool may_hide(const Cone& a, const Cone& b) {
  if (a.nearest >= b.farthest) return false;
  if (a.cos_half <= 0 || b.cos_half <= 0) return true;  // a half angle >= 90 degrees
  const double cos_sum = a.cos_half * b.cos_half - a.sin_half * b.sin_half;  // cos(alpha_a + alpha_b)
  return a.axis.dot(b.axis) >= cos_sum - 1e-12;
}

}  // namespace

std::vector<OctreeItem> octree_items(const Scene& scene, const std::vector<EmittingFace>& faces) {
  std::vector<OctreeItem> items;
  items.reserve(faces.size());
  for (const EmittingFace& f : faces) items.push_back({f.vertices, scene.polygons[f.polygon].normal, f.exitance});
  return items;
}

LocalPass::LocalPass(const Scene& scene, std::vector<EmittingFace> faces, ExactMethod method,
                     const OctreeSettings& settings)
    : faces_(std::move(faces)), method_(method), octree_(octree_items(scene, faces_), settings) {
  if (method_ == ExactMethod::hemisphere) {
    hemisphere_.emplace(scene, faces_);
  } else {
    tracer_.emplace(scene, faces_);
  }
  leaf_centre_.assign(octree_.voxels().size(), Vec3::Zero());
  leaf_radius_.assign(octree_.voxels().size(), 0.0);
  for (const int v : octree_.leaves()) {
    const auto& bounds = octree_.voxels()[v].bounds;
    leaf_centre_[v] = bounds.center();
    leaf_radius_[v] = 0.5 * bounds.diagonal().norm();
  }
}

Rgb LocalPass::gather_exact(const Vec3& x, const Vec3& n, const std::vector<char>& emitting) const {
  if (tracer_) {
    VertexTracer::Options options;
    options.emitting = &emitting;
    return tracer_->gather(x, n, options).irradiance;
  }
  return hemisphere_->gather(x, n).irradiance;  // every face radiates (tolerance 0)
}

LocalPassResult LocalPass::gather(const Vec3& x, const Vec3& n, double tolerance) const {
  LocalPassResult result;
  const std::vector<int>& leaves = octree_.leaves();
  std::vector<char> emitting(faces_.size(), 0);
  if (!(tolerance > 0)) {
    std::fill(emitting.begin(), emitting.end(), 1);
    result.irradiance = gather_exact(x, n, emitting);
    result.emitting = result.projected = static_cast<int>(faces_.size());
    result.voxels = static_cast<int>(leaves.size());
    result.gathers = 1;
    return result;
  }

  // Leaves by decreasing bound (eq. 8); a zero bound means nothing in the voxel lights x.
  struct Entry {
    double key;
    int voxel;
    Rgb bound, bmax;
  };
  std::vector<Entry> entries;
  for (const int v : leaves) {
    const Rgb bmax = octree_.bmax_toward(v, x, n);
    if (!(bmax.maxCoeff() > 0)) continue;
    const Rgb b = bmax * box_form_factor(octree_.voxels()[v].bounds, x, n);
    if (b.maxCoeff() > 0) entries.push_back({b.maxCoeff(), v, b, bmax});
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.key != b.key ? a.key > b.key : a.voxel < b.voxel;
  });
  // From entry i on: the sum of the bounds (eq. 9) and the largest bmax.
  std::vector<Rgb> bound_sum(entries.size() + 1, Rgb::Zero()), bmax_max(entries.size() + 1, Rgb::Zero());
  for (size_t i = entries.size(); i-- > 0;) {
    bound_sum[i] = bound_sum[i + 1] + entries[i].bound;
    bmax_max[i] = bmax_max[i + 1].cwiseMax(entries[i].bmax);
  }

  Rgb exact = Rgb::Zero();
  double covered = 0;  // form factor covered by the visible parts of the gathered faces
  size_t next = 0;
  // What the unselected faces can still add, certified (see the header): at most the sum of
  // their voxels' bounds, and, with the hemisphere's coverage, at most their largest radiosity
  // times the form factor left uncovered (their visible parts lie outside the gathered ones').
  const auto remainder = [&] {
    Rgb r = bound_sum[next];
    if (hemisphere_) r = r.cwiseMin(bmax_max[next] * std::max(0.0, 1 - covered));
    return r;
  };
  const auto done = [&] {
    const Rgb half = 0.5 * remainder();
    return next == entries.size() || half.maxCoeff() <= tolerance * (exact + half).maxCoeff();
  };
  std::optional<HemisphereGatherer::Session> session;
  if (hemisphere_) session.emplace(*hemisphere_, x, n);
  std::vector<Cone> cones;            // per leaf (index into leaves), made at the first batch
  std::vector<char> projected_voxel;  // per leaf: its faces were added to the session
  while (!done()) {
    std::vector<int> batch;
    if (session) {
      // Projection is incremental, so batches may be small: enough to halve the bound sum.
      const double target = 0.5 * bound_sum[next].maxCoeff();
      do {
        batch.push_back(entries[next++].voxel);
      } while (next < entries.size() && bound_sum[next].maxCoeff() > target);
    } else {
      // Each trace starts afresh: aim straight at the stopping rule with what is known of H,
      // before the first trace that the bound sum falls to tolerance times the whole, after it
      // that R <= 2 T H / (1 - T).
      const double target = result.gathers == 0 ? tolerance * bound_sum[0].maxCoeff()
                                                : 2 * tolerance * exact.maxCoeff() / std::max(1 - tolerance, 1e-12);
      do {
        batch.push_back(entries[next++].voxel);
      } while (next < entries.size() && bound_sum[next].maxCoeff() > target);
    }
    for (const int v : batch) {
      for (const int i : octree_.voxels()[v].items) emitting[i] = 1;
      result.emitting += static_cast<int>(octree_.voxels()[v].items.size());
    }
    result.voxels += static_cast<int>(batch.size());
    ++result.gathers;
    if (session) {
      // 004's SolveVisibility: with the batch, whatever may hide it (each voxel once).
      if (cones.empty()) {
        for (const int u : leaves) cones.push_back(cone_of(x, leaf_centre_[u], leaf_radius_[u]));
        projected_voxel.assign(leaves.size(), 0);
      }
      std::vector<Cone> targets;
      for (const int v : batch) targets.push_back(cone_of(x, leaf_centre_[v], leaf_radius_[v]));
      std::vector<int> faces;
      for (size_t u = 0; u < leaves.size(); ++u) {
        if (projected_voxel[u]) continue;
        if (std::any_of(targets.begin(), targets.end(), [&](const Cone& t) { return may_hide(cones[u], t); })) {
          projected_voxel[u] = 1;
          const auto& items = octree_.voxels()[leaves[u]].items;
          faces.insert(faces.end(), items.begin(), items.end());
        }
      }
      for (const int v : batch) {  // the batch itself (its own cone test may have been skipped)
        const auto& items = octree_.voxels()[v].items;
        faces.insert(faces.end(), items.begin(), items.end());
      }
      session->add(faces);
      exact = session->irradiance(emitting, &covered);
    } else {
      exact += gather_exact(x, n, emitting);
      result.projected += static_cast<int>(std::count(emitting.begin(), emitting.end(), 1));
      for (const int v : batch) {
        for (const int i : octree_.voxels()[v].items) emitting[i] = 0;
      }
    }
  }
  if (session) result.projected = session->added();
  result.bound = 0.5 * remainder();
  result.irradiance = exact + result.bound;
  return result;
}

}  // namespace rad
