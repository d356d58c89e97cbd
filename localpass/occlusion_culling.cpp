#include "localpass/occlusion_culling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <ranges>
#include <tuple>
#include <utility>

#include "geometry/shaft.h"
#include "geometry/tolerance.h"
#include "scene/polygon.h"

namespace rad {
namespace {

/// Whether two convex polygons in one plane (normal n) overlap with positive area: no edge of
/// either separates them by more than -tolerance (touching along an edge is not overlapping).
bool convex_overlap(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const Vec3& n,
                    double tolerance) {
  const auto separated_by_edges_of = [&](const std::vector<Vec3>& p, const std::vector<Vec3>& q) {
    const double orientation = newell_vector(p).dot(n) >= 0 ? 1 : -1;
    for (size_t i = 0; i < p.size(); ++i) {
      const Vec3 out = orientation * (p[(i + 1) % p.size()] - p[i]).cross(n);  // outward in-plane
      const double norm = out.norm();
      if (!(norm > 0)) continue;
      const double edge = out.dot(p[i]) / norm;
      const double nearest = std::ranges::min(
          q | std::views::transform([&](const Vec3& v) { return out.dot(v) / norm; }));
      if (nearest >= edge - tolerance) return true;
    }
    return false;
  };
  return !separated_by_edges_of(a, b) && !separated_by_edges_of(b, a);
}

}  // namespace

/// The range of the points' signed heights over the polygon's plane.
std::pair<double, double> OcclusionCulling::height_range(const PolygonData& polygon,
                                                         std::span<const Vec3> points) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Vec3& v : points) {
    const double h = polygon.normal.dot(v) - polygon.offset;
    lo = std::min(lo, h), hi = std::max(hi, h);
  }
  return {lo, hi};
}

OcclusionCulling::OcclusionCulling(const Scene& scene, const std::vector<EmittingFace>& faces,
                                   const Octree& octree)
    : faces_(faces), octree_(octree) {
  // The gatherers' own tolerance (Scene::tolerance()): the culling is exact only with it.
  const Tolerance tolerance = scene.tolerance();
  in_plane_ = tolerance.in_plane;
  pad_ = tolerance.pad;
  polygons_.resize(scene.polygons.size());
  for (size_t p = 0; p < scene.polygons.size(); ++p) {
    const Polygon& polygon = scene.polygons[p];
    PolygonData& data = polygons_[p];
    data.normal = polygon.normal;
    data.offset = polygon.normal.dot(polygon.vertices.front());
    data.vertices = polygon.vertices;
    data.box = bounding_box(polygon.vertices);
  }
  for (size_t f = 0; f < faces_.size(); ++f) {
    face_boxes_.push_back(bounding_box(faces_[f].vertices));
  }

  // Coplanar polygons that overlap (sort and sweep on the boxes, then in-plane overlap of the
  // convex pieces).
  const auto pieces =
      faces_from_polygons(scene, std::vector<Rgb>(scene.polygons.size(), Rgb::Zero()));
  std::vector<std::vector<int>> pieces_of(scene.polygons.size());
  for (size_t i = 0; i < pieces.size(); ++i)
    pieces_of[pieces[i].polygon].push_back(static_cast<int>(i));
  std::vector<int> order(scene.polygons.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::ranges::sort(
      order, [&](int a, int b) { return polygons_[a].box.min().x() < polygons_[b].box.min().x(); });
  for (size_t oi = 0; oi < order.size(); ++oi) {
    PolygonData& a = polygons_[order[oi]];
    for (size_t oj = oi + 1;
         oj < order.size() && polygons_[order[oj]].box.min().x() <= a.box.max().x() + pad_; ++oj) {
      PolygonData& b = polygons_[order[oj]];
      if (std::abs(a.normal.dot(b.normal)) < 1 - relative::kRounding) continue;
      if (std::ranges::any_of(b.vertices, [&](const Vec3& v) {
            return std::abs(a.normal.dot(v) - a.offset) > pad_;
          })) {
        continue;
      }
      bool overlap = false;
      for (const int i : pieces_of[order[oi]]) {
        for (const int j : pieces_of[order[oj]])
          overlap =
              overlap || convex_overlap(pieces[i].vertices, pieces[j].vertices, a.normal, pad_);
      }
      if (!overlap) continue;
      a.coplanar_overlapping.push_back(order[oj]);
      b.coplanar_overlapping.push_back(order[oi]);
    }
  }
}

bool OcclusionCulling::can_light(int face, const Vec3& x, const Vec3& n) const {
  const EmittingFace& f = faces_[face];
  if (!(f.exitance.maxCoeff() > 0)) return false;
  // The gatherers' tests: x strictly in front of the plane, and some part above the horizon.
  if (!(polygons_[f.polygon].normal.dot(f.vertices.front() - x) < -in_plane_)) return false;
  return std::ranges::any_of(f.vertices, [&](const Vec3& v) { return n.dot(v - x) > 0; });
}

void OcclusionCulling::filter(std::span<const int> candidates, const Vec3& x,
                              const Eigen::AlignedBox3d& box, const std::vector<Vec3>* face,
                              std::vector<int>* out) const {
  out->clear();
  const Vec3 centre = box.center(), half = 0.5 * box.sizes();
  for (const int p : candidates) {
    const PolygonData& polygon = polygons_[p];
    const double at_x = polygon.normal.dot(x) - polygon.offset;
    // Its plane must put some of the box (or of the face: a slanted face's box pokes through
    // the face's own plane) beyond it, seen from x.
    double lo, hi;
    if (face) {
      std::tie(lo, hi) = height_range(polygon, *face);
    } else {
      const double at_centre = polygon.normal.dot(centre) - polygon.offset;
      const double reach = polygon.normal.cwiseAbs().dot(half);
      lo = at_centre - reach, hi = at_centre + reach;
    }
    if (at_x > 0 ? lo < -in_plane_ : hi > in_plane_) out->push_back(p);
  }
  if (out->empty()) return;
  const Shaft shaft(x, box, pad_);
  std::erase_if(*out,
                [&](int p) { return !shaft.may_meet(polygons_[p].vertices, polygons_[p].box); });
}

void OcclusionCulling::occluders(const Vec3& x, const OcclusionSplit::Group& group,
                                 std::vector<int>* out) const {
  const Shaft shaft(x, group.box, pad_);
  std::vector<int> stack = {0};
  while (!stack.empty()) {
    const Voxel& voxel = octree_.voxels()[stack.back()];
    stack.pop_back();
    if (voxel.item_count == 0 || !shaft.may_meet(voxel.bounds)) continue;
    if (!voxel.is_leaf()) {
      for (int c = 0; c < 8; ++c) stack.push_back(voxel.first_child + c);
      continue;
    }
    for (const int g : voxel.items) {
      if (std::ranges::binary_search(group.blockers, faces_[g].polygon) &&
          shaft.may_meet(faces_[g].vertices, face_boxes_[g])) {
        out->push_back(g);
      }
    }
  }
}

bool OcclusionCulling::is_candidate(int p, const Vec3& x, const Vec3& n) const {
  const PolygonData& polygon = polygons_[p];
  if (std::abs(polygon.normal.dot(x) - polygon.offset) <= 0.5 * in_plane_) return false;
  return std::ranges::any_of(polygon.vertices, [&](const Vec3& v) { return n.dot(v - x) > 0; });
}

std::vector<int> OcclusionCulling::candidates(const Vec3& x, const Vec3& n) const {
  std::vector<int> candidates;
  for (size_t p = 0; p < polygons_.size(); ++p) {
    if (is_candidate(static_cast<int>(p), x, n)) candidates.push_back(static_cast<int>(p));
  }
  return candidates;
}

std::vector<int> OcclusionCulling::candidates(const Vec3& x, const Vec3& n,
                                              std::span<const int> polygons) const {
  std::vector<int> candidates;
  for (const int p : polygons) {
    if (is_candidate(p, x, n)) candidates.push_back(p);
  }
  return candidates;
}

void OcclusionCulling::blockers(std::span<const int> candidates, const Vec3& x,
                                const Eigen::AlignedBox3d& box, const std::vector<Vec3>& outline,
                                int polygon, std::vector<int>* out) const {
  filter(candidates, x, box, &outline, out);
  const std::vector<int>& coplanar = polygons_[polygon].coplanar_overlapping;
  if (coplanar.empty()) return;
  out->insert(out->end(), coplanar.begin(), coplanar.end());
  std::ranges::sort(*out);
  out->erase(std::unique(out->begin(), out->end()), out->end());
}

bool OcclusionCulling::may_hide_between(std::span<const Vec3> hull, double margin,
                                        const Eigen::AlignedBox3d& region,
                                        std::span<const Vec3> outline,
                                        const Eigen::AlignedBox3d& box, int polygon) const {
  if (!polygons_[polygon].coplanar_overlapping.empty()) return true;
  std::optional<Shaft> shaft;
  for (size_t p = 0; p < polygons_.size(); ++p) {
    if (static_cast<int>(p) == polygon) continue;  // its own plane hides none of it
    const PolygonData& data = polygons_[p];
    // filter()'s test for every x of the region that is_candidate keeps: x on one side by
    // more than half the tolerance, part of the box beyond the plane on the other. Over the
    // region, the height is affine: its range is that of the hull's points, widened by the
    // margin.
    auto [x_lo, x_hi] = height_range(data, hull);
    x_lo -= margin, x_hi += margin;
    const auto [b_lo, b_hi] = height_range(data, outline);
    const bool separates = (x_hi > 0.5 * in_plane_ && b_lo < -in_plane_) ||
                           (x_lo < -0.5 * in_plane_ && b_hi > in_plane_);
    if (!separates) continue;
    if (!shaft) shaft.emplace(region, box, pad_);
    if (shaft->may_meet(data.vertices, data.box)) return true;
  }
  return false;
}

OcclusionSplit OcclusionCulling::split_without_culling(const Vec3& x, const Vec3& n) const {
  OcclusionSplit split;
  OcclusionSplit::Group group;
  for (size_t f = 0; f < faces_.size(); ++f) {
    if (can_light(static_cast<int>(f), x, n)) group.faces.push_back(static_cast<int>(f));
  }
  if (group.faces.empty()) return split;
  for (size_t p = 0; p < polygons_.size(); ++p) group.blockers.push_back(static_cast<int>(p));
  group.box = octree_.voxels()[0].bounds;  // with x or not, its shaft holds every face
  split.shadowed.push_back(std::move(group));
  return split;
}

}  // namespace rad
