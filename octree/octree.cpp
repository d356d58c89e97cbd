#include "octree/octree.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "geometry/lambert.h"

namespace rad {
namespace {

Eigen::AlignedBox3d box_of(const OctreeItem& item) { return bounding_box(item.corners); }

Vec3 centroid_of(const OctreeItem& item) {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& c : item.corners) sum += c;
  return sum / static_cast<double>(item.corners.size());
}

/// Eq. 8's test: the item can send light to (x, n).
bool can_light(const OctreeItem& item, const Vec3& x, const Vec3& n) {
  if (!(item.normal.dot(x - item.corners.front()) > 0)) return false;  // x behind (or in) its plane
  for (const Vec3& c : item.corners) {
    if (n.dot(c - x) > 0) return true;
  }
  return false;
}

}  // namespace

Octree::Octree(std::vector<OctreeItem> items, const OctreeSettings& settings)
    : items_(std::move(items)) {
  Voxel root;
  for (const OctreeItem& item : items_) root.cell.extend(box_of(item));
  if (root.cell.isEmpty()) root.cell = Eigen::AlignedBox3d(Vec3::Zero(), Vec3::Zero());
  // A cube, so that children stay cubes.
  const double half = 0.5 * root.cell.sizes().maxCoeff();
  const Vec3 centre = root.cell.center();
  root.cell = Eigen::AlignedBox3d(centre - Vec3::Constant(half), centre + Vec3::Constant(half));
  voxels_.push_back(root);
  std::vector<int> all(items_.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  double root_proxy = 0;
  {
    Rgb bmax = Rgb::Zero();
    Eigen::AlignedBox3d bounds;
    for (const OctreeItem& item : items_) {
      bmax = bmax.cwiseMax(item.radiosity);
      bounds.extend(box_of(item));
    }
    root_proxy = items_.empty() ? 0 : bmax.maxCoeff() * bounds.sizes().squaredNorm();
  }
  build(0, std::move(all), settings, root_proxy);
}

void Octree::build(int v, std::vector<int> items, const OctreeSettings& settings,
                   double root_proxy) {
  Voxel& voxel = voxels_[v];
  voxel.item_count = static_cast<int>(items.size());
  for (const int i : items) {
    voxel.bounds.extend(box_of(items_[i]));
    voxel.bmax = voxel.bmax.cwiseMax(items_[i].radiosity);
  }
  const double proxy =
      items.empty() ? 0 : voxel.bmax.maxCoeff() * voxel.bounds.sizes().squaredNorm();
  const bool leaf = static_cast<int>(items.size()) <= settings.min_items ||
                    voxel.level >= settings.max_level ||
                    proxy <= settings.energy_fraction * root_proxy * std::ldexp(1.0, voxel.level);
  if (leaf) {
    if (!items.empty()) leaves_.push_back(v);
    voxel.items = std::move(items);
    return;
  }
  const Vec3 centre = voxel.cell.center();
  const Eigen::AlignedBox3d cell = voxel.cell;
  const int level = voxel.level;
  std::array<std::vector<int>, 8> children;
  for (const int i : items) {
    const Vec3 c = centroid_of(items_[i]);
    const int octant = (c.x() >= centre.x() ? 1 : 0) | (c.y() >= centre.y() ? 2 : 0) |
                       (c.z() >= centre.z() ? 4 : 0);
    children[octant].push_back(i);
  }
  const int first = static_cast<int>(voxels_.size());
  voxels_[v].first_child = first;  // `voxel` may dangle once voxels_ grows
  for (int octant = 0; octant < 8; ++octant) {
    Voxel child;
    child.level = level + 1;
    const Vec3 lo((octant & 1) ? centre.x() : cell.min().x(),
                  (octant & 2) ? centre.y() : cell.min().y(),
                  (octant & 4) ? centre.z() : cell.min().z());
    child.cell = Eigen::AlignedBox3d(lo, lo + 0.5 * cell.sizes());
    voxels_.push_back(child);
  }
  for (int octant = 0; octant < 8; ++octant)
    build(first + octant, std::move(children[octant]), settings, root_proxy);
}

long long Octree::max_voxels(long long items, const OctreeSettings& settings) {
  long long inner = 0, level_width = 1;  // 8^level, capped once it exceeds the items' share
  const long long per_level = items / (std::max(settings.min_items, 0) + 1);
  for (int level = 0; level < settings.max_level; ++level) {
    inner += std::min(level_width, per_level);
    level_width = std::min(level_width * 8, per_level + 1);
  }
  return 1 + 8 * inner;
}

std::vector<int> Octree::items_below(int v) const {
  std::vector<int> out;
  std::vector<int> stack{v};
  while (!stack.empty()) {
    const Voxel& voxel = voxels_[stack.back()];
    stack.pop_back();
    out.insert(out.end(), voxel.items.begin(), voxel.items.end());
    if (!voxel.is_leaf()) {
      for (int c = 0; c < 8; ++c) stack.push_back(voxel.first_child + c);
    }
  }
  return out;
}

Rgb Octree::bmax_toward(int v, const Vec3& x, const Vec3& n) const {
  const Voxel& voxel = voxels_[v];
  Rgb bmax = Rgb::Zero();
  if (voxel.is_leaf()) {
    for (const int i : voxel.items) {
      if (can_light(items_[i], x, n)) bmax = bmax.cwiseMax(items_[i].radiosity);
    }
    return bmax;
  }
  for (int c = 0; c < 8; ++c) {
    if (voxels_[voxel.first_child + c].item_count > 0)
      bmax = bmax.cwiseMax(bmax_toward(voxel.first_child + c, x, n));
  }
  return bmax;
}

Rgb Octree::bound_eq7(int v, const Vec3& x, const Vec3& n) const {
  const Voxel& voxel = voxels_[v];
  if (voxel.item_count == 0) return Rgb::Zero();
  return voxel.bmax * box_form_factor(voxel.bounds, x, n);
}

Rgb Octree::bound(int v, const Vec3& x, const Vec3& n) const {
  const Voxel& voxel = voxels_[v];
  if (voxel.item_count == 0) return Rgb::Zero();
  const Rgb bmax = bmax_toward(v, x, n);
  if (bmax == Rgb::Zero()) return bmax;
  return bmax * box_form_factor(voxel.bounds, x, n);
}

double box_form_factor(const Eigen::AlignedBox3d& box, const Vec3& x, const Vec3& n) {
  const Vec3 lo = box.min(), hi = box.max();
  if ((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all()) return 1;
  double sum = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    // The face at hi (outward +axis) is seen from outside when x is beyond it; the face at lo
    // when x is below it. At most one of the two.
    double at;
    if (x[axis] > hi[axis]) {
      at = hi[axis];
    } else if (x[axis] < lo[axis]) {
      at = lo[axis];
    } else {
      continue;
    }
    if (!(hi[a] > lo[a]) || !(hi[b] > lo[b])) continue;  // flat box: the face has no area
    std::vector<Vec3> face(4);
    const double us[4] = {lo[a], hi[a], hi[a], lo[a]}, vs[4] = {lo[b], lo[b], hi[b], hi[b]};
    for (int k = 0; k < 4; ++k) {
      face[k][axis] = at;
      face[k][a] = us[k];
      face[k][b] = vs[k];
    }
    sum += point_polygon_form_factor(x, n, face);
  }
  return std::min(sum, 1.0);
}

}  // namespace rad
