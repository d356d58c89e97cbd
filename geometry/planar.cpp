#include "geometry/planar.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "geometry/box_tree.h"
#include "geometry/tolerance.h"

namespace rad {

Vec3 newell_vector(const std::vector<Vec3>& vertices) {
  // Sum of cross products of consecutive vertices taken relative to the first vertex: the same
  // value as Newell's formula but with far less cancellation for polygons far from the origin.
  Vec3 sum = Vec3::Zero();
  const Vec3& o = vertices.front();
  for (size_t i = 1; i + 1 < vertices.size(); ++i) {
    sum += (vertices[i] - o).cross(vertices[i + 1] - o);
  }
  return sum;
}

double extent(const std::vector<Vec3>& vertices) {
  Vec3 lo = vertices.front(), hi = vertices.front();
  for (const Vec3& p : vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

double plane_deviation(const std::vector<Vec3>& vertices, const Vec3& n) {
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : vertices) centroid += p;
  centroid /= static_cast<double>(vertices.size());
  double deviation = 0;
  for (const Vec3& p : vertices) deviation = std::max(deviation, std::abs(n.dot(p - centroid)));
  return deviation;
}

PlaneFrame::PlaneFrame(const Vec3& origin_, const Vec3& unit_normal)
    : origin(origin_), n(unit_normal) {
  // Cross n with the coordinate axis least aligned with it: well conditioned for any n.
  Vec3 axis = Vec3::Zero();
  int least = 0;
  n.cwiseAbs().minCoeff(&least);
  axis[least] = 1;
  u = n.cross(axis).normalized();
  v = n.cross(u);
}

std::vector<Vec2> project_to_plane(const std::vector<Vec3>& vertices, const Vec3& n) {
  PlaneFrame frame(vertices.front(), n);
  std::vector<Vec2> out;
  out.reserve(vertices.size());
  for (const Vec3& p : vertices) out.push_back(frame.to_2d(p));
  return out;
}

namespace {

/// True when the closed segments [a,b] and [c,d] cross or come closer than `tolerance`.
bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, double tolerance) {
  const double d1 = cross_2d(b - a, c - a), d2 = cross_2d(b - a, d - a);
  const double d3 = cross_2d(d - c, a - c), d4 = cross_2d(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
    return true;  // proper crossing
  }
  const double gap = std::min({point_segment_distance(a, c, d), point_segment_distance(b, c, d),
                               point_segment_distance(c, a, b), point_segment_distance(d, a, b)});
  return gap <= tolerance;
}

}  // namespace

double signed_area_2d(const std::vector<Vec2>& polygon, const Vec2& about) {
  double twice_area = 0;
  const size_t n = polygon.size();
  for (size_t i = 0; i < n; ++i) {
    twice_area += cross_2d(polygon[i] - about, polygon[(i + 1) % n] - about);
  }
  return twice_area;
}

bool is_convex(const std::vector<Vec2>& polygon) {
  const double orientation = signed_area_2d(polygon) > 0 ? 1 : -1;
  const size_t n = polygon.size();
  for (size_t k = 0; k < n; ++k) {
    const Vec2 e0 = polygon[(k + 1) % n] - polygon[k];
    const Vec2 e1 = polygon[(k + 2) % n] - polygon[(k + 1) % n];
    if (orientation * cross_2d(e0, e1) < 0) return false;
  }
  return true;
}

std::vector<int> convex_hull(const std::vector<Vec2>& points) {
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::ranges::sort(order, [&](int a, int b) {
    return points[a].x() != points[b].x() ? points[a].x() < points[b].x()
                                          : points[a].y() < points[b].y();
  });
  order.erase(
      std::unique(order.begin(), order.end(), [&](int a, int b) { return points[a] == points[b]; }),
      order.end());
  if (order.size() < 3) return order;
  // Turn at b of the path o -> a -> b: positive when counter-clockwise.
  const auto turn = [&](int o, int a, int b) {
    return cross_2d(points[a] - points[o], points[b] - points[o]);
  };
  std::vector<int> hull(2 * order.size());
  size_t k = 0;
  for (const int i : order) {  // lower chain
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], i) <= 0) --k;
    hull[k++] = i;
  }
  for (size_t j = order.size() - 1, lower = k + 1; j-- > 0;) {  // upper chain
    const int i = order[j];
    while (k >= lower && turn(hull[k - 2], hull[k - 1], i) <= 0) --k;
    hull[k++] = i;
  }
  hull.resize(k - 1);
  return hull;
}

std::optional<std::pair<int, int>> find_self_intersection(const std::vector<Vec2>& polygon,
                                                          double tolerance) {
  const int n = static_cast<int>(polygon.size());
  // Two edges can cross or come within `tolerance` only if their boxes, each grown by it, meet:
  // a tree of the grown boxes names the candidates of each edge, and only those are tested,
  // in the order of the plain double loop (i, then j ascending), so the pair found is the same.
  // Neighbours share a vertex, so their boxes always meet and they are always tested.
  std::vector<Eigen::AlignedBox2d> boxes(n);
  for (int i = 0; i < n; ++i) {
    boxes[i].extend(polygon[i]);
    boxes[i].extend(polygon[(i + 1) % n]);
    boxes[i].min().array() -= tolerance;
    boxes[i].max().array() += tolerance;
  }
  const BoxTree<2> tree(boxes);
  std::vector<int> candidates;
  for (int i = 0; i < n; ++i) {
    candidates.clear();
    tree.query(boxes[i], [&](int j) {
      if (j > i) candidates.push_back(j);
    });
    std::ranges::sort(candidates);
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % n];
    for (const int j : candidates) {
      const Vec2& c = polygon[j];
      const Vec2& d = polygon[(j + 1) % n];
      const bool next = (j == i + 1);
      const bool wrap = (i == 0 && j == n - 1);
      if (next || wrap) {
        // Neighbours share one vertex q; they overlap only if they fold back onto each other.
        const Vec2 q = next ? b : a;
        const Vec2 p = next ? a : c;  // the far end of the earlier edge
        const Vec2 r = next ? d : b;  // the far end of the later edge
        const Vec2 in = q - p, out = r - q;
        const double scale = in.norm() * out.norm();
        if (std::abs(cross_2d(in, out)) <= relative::kRounding * scale && in.dot(out) < 0)
          return std::pair{i, j};
        continue;
      }
      if (segments_meet(a, b, c, d, tolerance)) return std::pair{i, j};
    }
  }
  return std::nullopt;
}

std::vector<std::array<int, 3>> triangulate(const std::vector<Vec2>& polygon) {
  const int n = static_cast<int>(polygon.size());
  std::vector<std::array<int, 3>> triangles;
  if (n < 3) return triangles;
  triangles.reserve(n - 2);
  const double orientation = signed_area_2d(polygon) >= 0 ? 1.0 : -1.0;

  std::vector<int> ring(n);
  std::iota(ring.begin(), ring.end(), 0);
  auto turn = [&](int a, int b, int c) {
    return orientation * cross_2d(polygon[b] - polygon[a], polygon[c] - polygon[b]);
  };
  auto inside_triangle = [&](const Vec2& p, int a, int b, int c) {
    // Inclusive test: a vertex on the ear's boundary blocks it, which keeps the result simple.
    const double w0 = orientation * cross_2d(polygon[b] - polygon[a], p - polygon[a]);
    const double w1 = orientation * cross_2d(polygon[c] - polygon[b], p - polygon[b]);
    const double w2 = orientation * cross_2d(polygon[a] - polygon[c], p - polygon[c]);
    return w0 >= 0 && w1 >= 0 && w2 >= 0;
  };

  while (ring.size() > 3) {
    const int m = static_cast<int>(ring.size());
    int ear = -1;
    for (int k = 0; k < m && ear < 0; ++k) {
      const int a = ring[(k + m - 1) % m], b = ring[k], c = ring[(k + 1) % m];
      if (turn(a, b, c) <= 0) continue;  // reflex or collinear: not an ear
      bool blocked = false;
      for (int other : ring) {
        if (other == a || other == b || other == c) continue;
        const Vec2& p = polygon[other];
        if (p == polygon[a] || p == polygon[b] || p == polygon[c]) continue;  // coincident copy
        if (inside_triangle(p, a, b, c)) {
          blocked = true;
          break;
        }
      }
      if (!blocked) ear = k;
    }
    if (ear < 0) {
      // No clean ear: only degenerate (collinear) corners remain, or the input was not simple.
      // Clip the corner that turns the most, so the triangle count stays #V-2.
      double best = -std::numeric_limits<double>::infinity();
      for (int k = 0; k < m; ++k) {
        const double t = turn(ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]);
        if (t > best) best = t, ear = k;
      }
    }
    triangles.push_back({ring[(ear + m - 1) % m], ring[ear], ring[(ear + 1) % m]});
    ring.erase(ring.begin() + ear);
  }
  triangles.push_back({ring[0], ring[1], ring[2]});
  return triangles;
}

bool contains_2d(const std::vector<Vec2>& polygon, const Vec2& p) {
  const size_t n = polygon.size();
  int winding = 0;
  for (size_t i = 0; i < n; ++i) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % n];
    const double side = cross_2d(b - a, p - a);
    // On the boundary: collinear and within the edge's extent.
    if (side == 0 && (p - a).dot(p - b) <= 0) return true;
    if (a.y() <= p.y()) {
      if (b.y() > p.y() && side > 0) ++winding;
    } else if (b.y() <= p.y() && side < 0) {
      --winding;
    }
  }
  return winding != 0;
}

}  // namespace rad
