#include "hemisphere/spherical_polygon.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "geometry/lambert.h"

namespace rad::hemi {
namespace {

constexpr double kOnPlane = 1e-15;  ///< |m . v| below this: v is on the plane (unit vectors)

/// Twice the area-like measure of a convex spherical fan: sum of triple products. Zero for
/// polygons that have collapsed onto a great circle.
double fan_measure(const Directions& v) {
  double sum = 0;
  for (size_t i = 1; i + 1 < v.size(); ++i) sum += v[0].dot(v[i].cross(v[i + 1]));
  return sum;
}

bool coincident(const Vec3& a, const Vec3& b) { return (a - b).squaredNorm() <= 1e-30; }

using Sides = boost::container::small_vector<double, 8>;

/// Whether the signs of the vertices' sides (s_i; 0: on the plane) are ones a convex polygon
/// can have: all on one side, or, going round, one run above and one run below, with vertices
/// on the plane only where one run meets the other (a run of them there: nearly coincident
/// vertices). A vertex on the plane between two below it means the polygon touches the plane
/// there and lies below it, so with a vertex above elsewhere the pattern is rounding's.
bool convex_pattern(const Sides& s) {
  const size_t count = s.size();
  const auto sign = [&](size_t i) { return s[i % count] > 0 ? 1 : s[i % count] < 0 ? -1 : 0; };
  size_t start = count;  // a vertex below that follows one that is not
  for (size_t i = 0; i < count && start == count; ++i)
    if (sign(i) < 0 && sign(i + count - 1) >= 0) start = i;
  if (start == count) return true;  // nothing below, or all below
  // The runs from `start` round: below, [on], above, [on], and nothing else.
  int runs[4], run_count = 0;
  for (size_t k = 0; k < count; ++k) {
    const int c = sign(start + k);
    if (run_count > 0 && runs[run_count - 1] == c) continue;
    if (run_count == 4) return false;
    runs[run_count++] = c;
  }
  static constexpr int kRuns[][4] = {{-1, 1}, {-1, 0, 1}, {-1, 1, 0}, {-1, 0, 1, 0}};
  static constexpr int kLengths[] = {2, 3, 3, 4};
  for (int p = 0; p < 4; ++p)
    if (run_count == kLengths[p] && std::equal(runs, runs + run_count, kRuns[p])) return true;
  // Nothing above: below and on the plane only (the polygon touches it).
  return std::none_of(runs, runs + run_count, [](int c) { return c > 0; });
}

}  // namespace

SphericalPolygon::SphericalPolygon(const std::vector<Vec3>& directions) {
  Directions unit;
  for (const Vec3& d : directions) {
    const double len = d.norm();
    if (!(len > 0)) continue;
    const Vec3 u = d / len;
    if (unit.empty() || !coincident(u, unit.back())) unit.push_back(u);
  }
  while (unit.size() > 1 && coincident(unit.front(), unit.back())) unit.pop_back();
  if (unit.size() < 3) return;
  const double measure = fan_measure(unit);
  if (!(std::abs(measure) > 1e-28)) return;  // collapsed onto a great circle: no area
  if (measure < 0) std::reverse(unit.begin(), unit.end());
  // Edge planes from the input directions; the caller's polygon edges are not degenerate.
  Directions normals;
  for (size_t i = 0; i < unit.size(); ++i)
    normals.push_back(unit[i].cross(unit[(i + 1) % unit.size()]).normalized());
  for (const Vec3& n : normals) {
    if (!n.allFinite()) return;
  }
  vertices_ = std::move(unit);
  normals_ = std::move(normals);
}

SphericalPolygon::SphericalPolygon(const Directions& vertices, const Directions& normals) {
  // Merge coincident consecutive vertices: the zero-length edge between them disappears, the
  // merged vertex keeps the later vertex's outgoing edge.
  Directions v, n;
  for (size_t i = 0; i < vertices.size(); ++i) {
    if (!v.empty() && coincident(vertices[i], v.back())) {
      n.back() = normals[i];
      continue;
    }
    v.push_back(vertices[i]);
    n.push_back(normals[i]);
  }
  while (v.size() > 1 && coincident(v.front(), v.back())) {
    v.pop_back();
    n.pop_back();
  }
  if (v.size() < 3 || !(fan_measure(v) > 1e-28)) return;
  vertices_ = std::move(v);
  normals_ = std::move(n);
}

bool SphericalPolygon::contains(const Vec3& d) const {
  if (empty()) return false;
  const Vec3 u = d.normalized();
  for (const Vec3& n : normals_) {
    if (n.dot(u) < -kOnPlane) return false;
  }
  return true;
}

std::optional<Vec3> arc_intersection(const Vec3& a0, const Vec3& a1, const Vec3& b0,
                                     const Vec3& b1) {
  const Vec3 na = a0.cross(a1), nb = b0.cross(b1);
  const Vec3 line = na.cross(nb);
  const double length = line.norm();
  if (!(length > 1e-15 * na.norm() * nb.norm())) return std::nullopt;  // one great circle
  for (const Vec3& p : {Vec3(line / length), Vec3(-line / length)}) {
    // p is within arc a when it lies between a0 and a1: on the inner side of both end planes.
    const bool in_a = a0.cross(p).dot(na) > 0 && p.cross(a1).dot(na) > 0;
    const bool in_b = b0.cross(p).dot(nb) > 0 && p.cross(b1).dot(nb) > 0;
    if (in_a && in_b) return p;
  }
  return std::nullopt;
}

int SphericalPolygon::side_of(const Vec3& m) const {
  bool any_pos = false, any_neg = false;
  for (const Vec3& v : vertices_) {
    const double s = m.dot(v);
    any_pos |= s > kOnPlane;
    any_neg |= s < -kOnPlane;
  }
  return any_neg ? (any_pos ? 0 : -1) : 1;
}

std::pair<SphericalPolygon, SphericalPolygon> SphericalPolygon::split(const Vec3& m) const {
  const size_t count = vertices_.size();
  Sides s(count);
  for (size_t i = 0; i < count; ++i) {
    s[i] = m.dot(vertices_[i]);
    if (std::abs(s[i]) <= kOnPlane) s[i] = 0;
  }
  // Rounding can put vertices that lie on the plane (a chain of collinear vertices along an edge
  // the plane runs through) a few ulps to either side of it, in an order no convex polygon has;
  // Sutherland-Hodgman then builds a sliver whose stored edge planes run out and back with the
  // same normal, and Lambert's formula gives it a large form factor (issue 36). Such a pattern
  // comes from rounding alone, so the smallest offsets go onto the plane until it is convex.
  while (!convex_pattern(s)) {
    double smallest = std::numeric_limits<double>::infinity();
    for (const double si : s)
      if (si != 0) smallest = std::min(smallest, std::abs(si));
    for (double& si : s)
      if (std::abs(si) <= smallest) si = 0;
  }
  bool any_pos = false, any_neg = false;
  for (const double si : s) any_pos |= si > 0, any_neg |= si < 0;
  if (!any_neg) return {*this, SphericalPolygon()};
  if (!any_pos) return {SphericalPolygon(), *this};

  // Sutherland-Hodgman for both sides at once. Each output vertex carries the normal of its
  // outgoing edge: an original edge keeps its normal, the cut gets +m (positive part) or -m.
  Directions pos_v, pos_n, neg_v, neg_n;
  for (size_t i = 0; i < count; ++i) {
    const size_t j = (i + 1) % count;
    const Vec3& vi = vertices_[i];
    const Vec3& ni = normals_[i];
    const double si = s[i], sj = s[j];
    // Positive side.
    if (si > 0 || (si == 0 && sj >= 0)) {
      pos_v.push_back(vi);
      pos_n.push_back(ni);
    } else if (si == 0 && sj < 0) {
      pos_v.push_back(vi);  // on the plane, the edge leaves: the cut follows
      pos_n.push_back(m);
    }
    // Negative side.
    if (si < 0 || (si == 0 && sj <= 0)) {
      neg_v.push_back(vi);
      neg_n.push_back(ni);
    } else if (si == 0 && sj > 0) {
      neg_v.push_back(vi);
      neg_n.push_back(-m);
    }
    if ((si > 0 && sj < 0) || (si < 0 && sj > 0)) {
      // The chord point where m . d = 0, normalized: on the edge's great circle and on m's.
      const Vec3 crossing = ((si * vertices_[j] - sj * vi) / (si - sj)).normalized();
      if (si > 0) {  // leaving the positive side: positive gets the cut, negative the edge
        pos_v.push_back(crossing);
        pos_n.push_back(m);
        neg_v.push_back(crossing);
        neg_n.push_back(ni);
      } else {
        neg_v.push_back(crossing);
        neg_n.push_back(-m);
        pos_v.push_back(crossing);
        pos_n.push_back(ni);
      }
    }
  }
  return {SphericalPolygon(pos_v, pos_n), SphericalPolygon(neg_v, neg_n)};
}

Vec3 SphericalPolygon::interior_direction() const {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& v : vertices_) sum += v;
  return sum.normalized();
}

std::vector<SphericalPolygon> intersect(const SphericalPolygon& a, const SphericalPolygon& b) {
  SphericalPolygon inside = a;
  for (size_t i = 0; i < b.vertices().size() && !inside.empty(); ++i)
    inside = inside.split(b.edge_normal(i)).first;
  if (inside.empty()) return {};
  return {inside};
}

std::vector<SphericalPolygon> subtract(const SphericalPolygon& a, const SphericalPolygon& b) {
  std::vector<SphericalPolygon> out;
  SphericalPolygon rest = a;
  for (size_t i = 0; i < b.vertices().size() && !rest.empty(); ++i) {
    auto [in, outside] = rest.split(b.edge_normal(i));
    if (!outside.empty()) out.push_back(std::move(outside));
    rest = std::move(in);
  }
  return out;
}

double SphericalPolygon::form_factor(const Vec3& n) const {
  if (empty()) return 0.0;
  // Lambert with the stored edge normals: exact planes even for very short edges.
  double sum = 0;
  for (size_t i = 0; i < vertices_.size(); ++i) {
    sum += lambert_edge(vertices_[i], vertices_[(i + 1) % vertices_.size()], n, normals_[i]);
  }
  return std::abs(sum) / (2 * std::numbers::pi);
}

double form_factor_with_holes(const std::vector<Vec3>& outer,
                              const std::vector<std::vector<Vec3>>& holes, const Vec3& n) {
  double sum = lambert_loop(outer, n);
  for (const auto& hole : holes) sum += lambert_loop(hole, n);
  return std::abs(sum);
}

}  // namespace rad::hemi
