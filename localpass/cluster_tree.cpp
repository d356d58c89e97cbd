#include "localpass/cluster_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "geometry/planar.h"
#include "geometry/tolerance.h"

namespace rad {

/// One polygon's faces in 2D coordinates (u, v) of its plane, with (u, v, normal) right-handed,
/// so that counter-clockwise in (u, v) is counter-clockwise about the normal.
struct ClusterTree::Flat {
  const std::vector<EmittingFace>* faces = nullptr;
  Vec3 normal = Vec3::UnitZ();
  std::vector<std::vector<Vec2>> points;  ///< Per face (indexed like faces), its vertices in 2D
  std::vector<Vec2> centroids;  ///< Per face, the mean of its vertices (to order and split)
  std::vector<Vec3> centers;    ///< Per face, its area centroid
  std::vector<double> areas;
  double eps = 0;  ///< "On the line": 1e-9 of the polygon's extent

  Vec2 flatten(const Vec3& p, const Vec3& u, const Vec3& v) const { return {u.dot(p), v.dot(p)}; }
};

namespace {

/// The area centroid of a convex polygon, by its fan of triangles (the vertex mean if it has
/// no area).
Vec3 area_centroid(const std::vector<Vec3>& vertices) {
  Vec3 sum = Vec3::Zero(), mean = Vec3::Zero();
  double area = 0;
  for (const Vec3& v : vertices) mean += v;
  mean /= static_cast<double>(vertices.size());
  for (size_t i = 1; i + 1 < vertices.size(); ++i) {
    const double a = (vertices[i] - vertices[0]).cross(vertices[i + 1] - vertices[0]).norm();
    sum += a * (vertices[0] + vertices[i] + vertices[i + 1]) / 3;
    area += a;
  }
  return area > 0 ? Vec3(sum / area) : mean;
}

}  // namespace

ClusterTree::ClusterTree(const std::vector<EmittingFace>& faces) {
  std::map<int, std::vector<int>> by_polygon;
  for (size_t f = 0; f < faces.size(); ++f)
    by_polygon[faces[f].polygon].push_back(static_cast<int>(f));
  Flat flat;
  flat.faces = &faces;
  flat.points.resize(faces.size());
  flat.centroids.resize(faces.size());
  flat.centers.resize(faces.size());
  flat.areas.resize(faces.size());
  for (auto& [polygon, members] : by_polygon) {
    const Vec3 normal = faces[members.front()].normal;
    const Vec3 u = normal.unitOrthogonal(), v = normal.cross(u);
    flat.normal = normal;
    Eigen::AlignedBox2d extent;
    for (const int f : members) {
      std::vector<Vec2>& p = flat.points[f];
      p.clear();
      Vec2 sum = Vec2::Zero();
      for (const Vec3& q : faces[f].vertices) {
        p.push_back(flat.flatten(q, u, v));
        sum += p.back();
        extent.extend(p.back());
      }
      flat.centroids[f] = sum / static_cast<double>(p.size());
      flat.areas[f] = 0.5 * std::abs(signed_area_2d(p, Vec2::Zero()));
      flat.centers[f] = area_centroid(faces[f].vertices);
    }
    flat.eps = relative::kMatch * extent.sizes().norm();
    roots_.push_back(build(flat, members));
  }
}

int ClusterTree::build(const Flat& flat, std::vector<int> members) {
  const std::vector<EmittingFace>& faces = *flat.faces;
  const int index = static_cast<int>(clusters_.size());
  clusters_.emplace_back();
  {
    Cluster& c = clusters_.back();
    c.polygon = faces[members.front()].polygon;
    c.normal = flat.normal;
    c.face_count = static_cast<int>(members.size());
    c.first_face = static_cast<int>(face_order_.size());  // leaves are made depth first
    c.bmin = Rgb::Constant(std::numeric_limits<double>::infinity());
    std::vector<Vec2> points;
    std::vector<const Vec3*> corners;
    double face_area = 0;
    Rgb power = Rgb::Zero();
    for (const int f : members) {
      c.bmin = c.bmin.cwiseMin(faces[f].exitance);
      c.bmax = c.bmax.cwiseMax(faces[f].exitance);
      face_area += flat.areas[f];
      power += flat.areas[f] * faces[f].exitance;
      for (size_t k = 0; k < faces[f].vertices.size(); ++k) {
        points.push_back(flat.points[f][k]);
        corners.push_back(&faces[f].vertices[k]);
      }
    }
    if (members.size() == 1) {
      c.face = members.front();
      face_order_.push_back(c.face);
      c.outline = faces[c.face].vertices;
    } else {
      std::vector<Vec2> hull_points;
      for (const int i : convex_hull(points)) {
        c.outline.push_back(*corners[i]);
        hull_points.push_back(points[i]);
      }
      const double outline_area = 0.5 * std::abs(signed_area_2d(hull_points, Vec2::Zero()));
      c.fills_outline = std::abs(outline_area - face_area) <= relative::kMatch * outline_area;
      c.gap_area = std::abs(outline_area - face_area) + relative::kRounding * outline_area;
    }
    if (members.size() == 1) c.fills_outline = true;
    c.face_area = face_area;
    c.bmean = face_area > 0 ? Rgb(power / face_area) : c.bmax;
    c.bspread = (c.bmax - c.bmean).cwiseMax(c.bmean - c.bmin).cwiseMax(0.0);
    if (face_area > 0) {
      for (const int f : members) c.center += flat.areas[f] * flat.centers[f];
      c.center /= face_area;
    } else {
      c.center = flat.centers[members.front()];
    }
    for (const int f : members) {
      const Rgb deviation = faces[f].exitance - c.bmean;
      c.babs += flat.areas[f] * deviation.cwiseAbs();
      c.moment += flat.areas[f] * (flat.centers[f] - c.center) * deviation.transpose();
    }
    for (const Vec3& v : c.outline) c.radius = std::max(c.radius, (v - c.center).norm());
    c.box = bounding_box(c.outline);
  }
  if (members.size() == 1) return index;

  // A clean cut: the line through an edge of a face near the middle, with no face across it.
  // Lines from the faces nearest the median centroid along the longer side are tried first.
  Eigen::AlignedBox2d spread;
  for (const int f : members) spread.extend(flat.centroids[f]);
  const int axis = spread.sizes().x() >= spread.sizes().y() ? 0 : 1;
  std::ranges::sort(members, [&](int a, int b) {
    return flat.centroids[a][axis] != flat.centroids[b][axis]
               ? flat.centroids[a][axis] < flat.centroids[b][axis]
               : a < b;
  });
  const size_t middle = members.size() / 2;
  std::vector<int> left, right, best_left, best_right;
  size_t best_balance = 0;
  for (size_t r = 0; r < std::min<size_t>(members.size(), 8) && 4 * best_balance < members.size();
       ++r) {
    // Faces at the median, then alternately above and below it.
    const size_t at = r % 2 == 0 ? middle + r / 2 : middle - (r + 1) / 2;
    if (at >= members.size()) continue;
    const std::vector<Vec2>& p = flat.points[members[at]];
    for (size_t k = 0; k < p.size(); ++k) {
      const Vec2 a = p[k], b = p[(k + 1) % p.size()];
      const Vec2 d = b - a;
      const double length = d.norm();
      if (!(length > 0)) continue;
      left.clear(), right.clear();
      bool clean = true;
      for (const int f : members) {
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const Vec2& q : flat.points[f]) {
          const double s = cross_2d(d, q - a) / length;
          lo = std::min(lo, s), hi = std::max(hi, s);
        }
        if (lo < -flat.eps && hi > flat.eps) {
          clean = false;
          break;
        }
        (hi <= flat.eps ? right : left).push_back(f);
      }
      const size_t balance = std::min(left.size(), right.size());
      if (clean && balance > best_balance) {
        best_balance = balance;
        best_left = left, best_right = right;
      }
    }
  }
  if (best_balance == 0) {  // no clean cut: the median of the centroids
    best_left.assign(members.begin(), members.begin() + static_cast<long>(middle));
    best_right.assign(members.begin() + static_cast<long>(middle), members.end());
  }
  const int a = build(flat, std::move(best_left));
  const int b = build(flat, std::move(best_right));
  clusters_[index].children = {a, b};
  return index;
}

}  // namespace rad
