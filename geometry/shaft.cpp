#include "geometry/shaft.h"

#include <algorithm>

#include "geometry/clip.h"

namespace rad {

Shaft::Shaft(const Vec3& x, Eigen::AlignedBox3d box, double pad) : pad_(pad) {
  box.min().array() -= pad;
  box.max().array() += pad;
  hull_box_ = box;
  hull_box_.extend(x);
  const Vec3 lo = box.min(), hi = box.max();
  // Per axis: which face x sees (+1 the face at hi, -1 at lo, 0 neither: x within the slab).
  int side[3];
  for (int a = 0; a < 3; ++a) side[a] = x[a] > hi[a] ? 1 : x[a] < lo[a] ? -1 : 0;
  // The box faces x does not see bound the hull: x lies on their inner side too.
  for (int a = 0; a < 3; ++a) {
    if (side[a] != 1) planes_[plane_count_++] = {Vec3::Unit(a), hi[a]};
    if (side[a] != -1) planes_[plane_count_++] = {-Vec3::Unit(a), -lo[a]};
  }
  // Silhouette edges (between a face x sees and one it does not) span a plane with x each.
  // An edge runs along axis c; its two faces are across axes a and b.
  for (int c = 0; c < 3; ++c) {
    const int a = (c + 1) % 3, b = (c + 2) % 3;
    for (int ea = -1; ea <= 1; ea += 2) {
      for (int eb = -1; eb <= 1; eb += 2) {
        const bool sees_a = side[a] == ea, sees_b = side[b] == eb;
        if (sees_a == sees_b) continue;
        Vec3 corner = lo;
        corner[a] = ea > 0 ? hi[a] : lo[a];
        corner[b] = eb > 0 ? hi[b] : lo[b];
        Vec3 normal = Vec3::Unit(c).cross(corner - x);
        if (!(normal.norm() > 0)) continue;
        normal.normalize();
        // Orient it away from the box: the diagonally opposite edge lies inside.
        Vec3 opposite = corner;
        opposite[a] = ea > 0 ? lo[a] : hi[a];
        opposite[b] = eb > 0 ? lo[b] : hi[b];
        if (normal.dot(opposite - x) > 0) normal = -normal;
        planes_[plane_count_++] = {normal, normal.dot(x)};
      }
    }
  }
}

Shaft::Shaft(const Eigen::AlignedBox3d& from, const Eigen::AlignedBox3d& box, double pad)
    : Shaft(from.center(), box, pad) {
  const double rho = 0.5 * from.diagonal().norm();
  pad_ += rho;
  Eigen::AlignedBox3d grown = from;
  grown.min().array() -= pad_;
  grown.max().array() += pad_;
  hull_box_.extend(grown);
}

bool Shaft::may_meet(const std::vector<Vec3>& vertices) const {
  return may_meet(vertices, bounding_box(vertices));
}

bool Shaft::may_meet(const std::vector<Vec3>& vertices,
                     const Eigen::AlignedBox3d& vertex_box) const {
  if (!hull_box_.intersects(vertex_box)) return false;
  // The cheap test first: every vertex beyond one plane.
  for (int i = 0; i < plane_count_; ++i) {
    const Plane& p = planes_[i];
    if (std::ranges::all_of(vertices,
                            [&](const Vec3& v) { return p.normal.dot(v) > p.offset + pad_; }))
      return false;
  }
  // Clip the polygon by every plane of the shaft (Sutherland-Hodgman): what is left lies in the
  // shaft (and, for a convex polygon, is exactly their intersection). A polygon spanning the
  // shaft's cross-section with its vertices all around it is rejected too, which testing the
  // vertices alone cannot do: a wall next to the box, beyond which the box pokes out.
  // Each plane adds at most one vertex: stack buffers for the usual small polygons.
  constexpr size_t kStack = 32;
  const size_t capacity = vertices.size() + static_cast<size_t>(plane_count_) + 1;
  std::array<Vec3, kStack> stack_a, stack_b;
  std::vector<Vec3> heap_a, heap_b;
  Vec3* polygon = stack_a.data();
  Vec3* clipped = stack_b.data();
  if (capacity > kStack) {
    heap_a.resize(capacity), heap_b.resize(capacity);
    polygon = heap_a.data(), clipped = heap_b.data();
  }
  size_t count = vertices.size();
  std::copy(vertices.begin(), vertices.end(), polygon);
  for (int i = 0; i < plane_count_ && count > 0; ++i) {
    const Plane& p = planes_[i];
    const double limit = p.offset + pad_;
    size_t kept = 0;
    // Inside is normal . v <= limit: the distance is the negated excess (negation is exact).
    clip_loop(
        polygon, count, [&](const Vec3& v) { return -(p.normal.dot(v) - limit); },
        interpolated_crossing, [&](const Vec3& v, int) { clipped[kept++] = v; });
    std::swap(polygon, clipped);
    count = kept;
  }
  return count > 0;
}

bool Shaft::may_meet(const Eigen::AlignedBox3d& box) const {
  if (!hull_box_.intersects(box)) return false;
  const Vec3 centre = box.center(), half = 0.5 * box.sizes();
  for (int i = 0; i < plane_count_; ++i) {
    const Plane& p = planes_[i];
    // The box's nearest corner to the plane's inside.
    if (p.normal.dot(centre) - p.normal.cwiseAbs().dot(half) > p.offset + pad_) return false;
  }
  return true;
}

}  // namespace rad
