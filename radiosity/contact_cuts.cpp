#include "radiosity/contact_cuts.h"

#include <algorithm>
#include <cmath>

#include "geometry/planar.h"
#include "scene/polygon.h"

namespace rad {
namespace {

using Piece = std::vector<Vec2>;

struct Segment {
  Vec2 a, b;
};

/// Where polygon q meets the plane (origin o, unit normal n) and rises in front of it: the
/// segment between the extreme points of the intersection (for a convex q, the intersection
/// itself; for a concave one it may also span a gap, which only adds a cut). False when q does
/// not reach the front, lies in the plane, or meets it in a point.
bool meeting_segment(const Polygon& q, const Vec3& o, const Vec3& n, double pad, Vec3* a, Vec3* b) {
  std::vector<double> h(q.vertices.size());
  double highest = -1;
  for (size_t j = 0; j < h.size(); ++j) {
    h[j] = n.dot(q.vertices[j] - o);
    highest = std::max(highest, h[j]);
  }
  if (!(highest > pad)) return false;
  std::vector<Vec3> points;
  for (size_t j = 0; j < h.size(); ++j) {
    const size_t k = (j + 1) % h.size();
    if (std::abs(h[j]) <= pad) points.push_back(q.vertices[j]);
    if ((h[j] < -pad && h[k] > pad) || (h[j] > pad && h[k] < -pad)) {
      const double t = h[j] / (h[j] - h[k]);
      points.push_back(q.vertices[j] + t * (q.vertices[k] - q.vertices[j]));
    }
  }
  if (points.size() < 2) return false;
  // The two points farthest apart.
  double longest = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    for (size_t j = i + 1; j < points.size(); ++j) {
      const double d = (points[i] - points[j]).squaredNorm();
      if (d > longest) longest = d, *a = points[i], *b = points[j];
    }
  }
  return longest > 0;
}

/// Length of the part of segment s strictly inside the convex piece (counter-clockwise), by
/// clipping its parameter range against each edge (Cyrus-Beck); `pad` shrinks the piece.
double inside_length(const Segment& s, const Piece& piece, double pad) {
  double t0 = 0, t1 = 1;
  const Vec2 d = s.b - s.a;
  for (size_t i = 0; i < piece.size(); ++i) {
    const Vec2& p = piece[i];
    const Vec2 e = piece[(i + 1) % piece.size()] - p;
    const double length = e.norm();
    if (!(length > 0)) continue;
    // Signed distance inside the edge: cross_2d(e, x - p) / |e| >= pad.
    const double at_a = cross_2d(e, s.a - p) / length - pad;
    const double rate = cross_2d(e, d) / length;
    if (rate == 0) {
      if (at_a < 0) return 0;
    } else if (rate > 0) {
      t0 = std::max(t0, -at_a / rate);
    } else {
      t1 = std::min(t1, -at_a / rate);
    }
    if (t0 >= t1) return 0;
  }
  return (t1 - t0) * d.norm();
}

/// The piece cut by the line through s: the part on each side (Sutherland-Hodgman), each kept
/// when it has area. Vertices within `pad` of the line go to both.
std::vector<Piece> cut(const Piece& piece, const Segment& s, double pad) {
  const Vec2 d = (s.b - s.a).normalized();
  std::vector<double> side(piece.size());
  for (size_t i = 0; i < piece.size(); ++i) side[i] = cross_2d(d, piece[i] - s.a);
  std::vector<Piece> out;
  for (const double sign : {1.0, -1.0}) {
    Piece half;
    for (size_t i = 0; i < piece.size(); ++i) {
      const size_t j = (i + 1) % piece.size();
      const double si = sign * side[i], sj = sign * side[j];
      if (si >= -pad) half.push_back(piece[i]);
      if ((si > pad && sj < -pad) || (si < -pad && sj > pad))
        half.push_back(piece[i] + (si / (si - sj)) * (piece[j] - piece[i]));
    }
    if (half.size() >= 3 && signed_area_2d(half) > pad * pad) out.push_back(std::move(half));
  }
  return out;
}

/// The piece without the corners that lie on the straight line through their neighbours (where
/// a cut ended on an edge): the mesher then sees a triangle as a triangle.
Piece without_straight_corners(const Piece& piece, double pad) {
  Piece out;
  for (size_t i = 0; i < piece.size(); ++i) {
    const Vec2& a = piece[(i + piece.size() - 1) % piece.size()];
    const Vec2& b = piece[i];
    const Vec2& c = piece[(i + 1) % piece.size()];
    const double base = (c - a).norm();
    if (base > 0 && std::abs(cross_2d(c - a, b - a)) / base > pad) out.push_back(b);
  }
  return out;
}

}  // namespace

NearPolygons::NearPolygons(const Scene& scene) : scene_(scene), pad_(scene.tolerance().pad) {
  const Bounds bounds = scene.bounds();
  // About two cells a polygon, at most 256 along an axis, cubes where the scene allows.
  const Vec3 extent = (bounds.hi - bounds.lo).cwiseMax(Vec3::Constant(1e-9));
  const double target = std::max<double>(1, 2.0 * static_cast<double>(scene.polygons.size()));
  const double side = std::cbrt(extent.prod() / target);
  for (int a = 0; a < 3; ++a)
    cells_[a] = std::clamp(static_cast<int>(extent[a] / std::max(side, 1e-12)), 1, 256);
  origin_ = bounds.lo;
  size_ = extent.cwiseQuotient(Vec3(cells_[0], cells_[1], cells_[2]));
  members_.resize(static_cast<size_t>(cells_[0]) * cells_[1] * cells_[2]);
  for (int i = 0; i < static_cast<int>(scene.polygons.size()); ++i) {
    int low[3], high[3];
    cell_range(i, low, high);
    for (int z = low[2]; z <= high[2]; ++z)
      for (int y = low[1]; y <= high[1]; ++y)
        for (int x = low[0]; x <= high[0]; ++x) members_[cell(x, y, z)].push_back(i);
  }
}

void NearPolygons::cell_range(int index, int low[3], int high[3]) const {
  const Polygon& p = scene_.polygons[index];
  Vec3 lo = p.vertices[0], hi = p.vertices[0];
  for (const Vec3& v : p.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  for (int a = 0; a < 3; ++a) {
    const auto at = [&](double coordinate) {
      return std::clamp(static_cast<int>(std::floor((coordinate - origin_[a]) / size_[a])), 0,
                        cells_[a] - 1);
    };
    low[a] = at(lo[a] - pad_);
    high[a] = at(hi[a] + pad_);
  }
}

std::vector<int> NearPolygons::of(int index) const {
  int low[3], high[3];
  cell_range(index, low, high);
  std::vector<int> out;
  for (int z = low[2]; z <= high[2]; ++z)
    for (int y = low[1]; y <= high[1]; ++y)
      for (int x = low[0]; x <= high[0]; ++x) {
        const std::vector<int>& m = members_[cell(x, y, z)];
        out.insert(out.end(), m.begin(), m.end());
      }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<std::vector<Vec3>> contact_pieces(const Scene& scene, int index, int max_cuts,
                                              const NearPolygons* near) {
  const Polygon& p = scene.polygons[index];
  const double pad = near ? near->pad() : scene.tolerance().pad;
  const PlaneFrame frame(p.vertices[0], p.normal);
  Piece outline;
  for (const Vec3& v : p.vertices) outline.push_back(frame.to_2d(v));
  std::vector<Piece> pieces;
  if (is_convex(outline)) {
    pieces.push_back(outline);
  } else {
    for (const auto& t : triangulate(outline))
      pieces.push_back({outline[t[0]], outline[t[1]], outline[t[2]]});
  }

  // The segments, longest first (ties: scene order), that cross some piece's inside.
  Vec3 low = p.vertices[0], high = p.vertices[0];
  for (const Vec3& v : p.vertices) low = low.cwiseMin(v), high = high.cwiseMax(v);
  std::vector<std::pair<double, Segment>> segments;
  // In scene order either way: the stable sort below keeps ties so.
  std::vector<int> candidates;
  if (near) {
    candidates = near->of(index);
  } else {
    candidates.resize(scene.polygons.size());
    for (size_t i = 0; i < candidates.size(); ++i) candidates[i] = static_cast<int>(i);
  }
  for (const int i : candidates) {
    if (i == index) continue;
    const Polygon& q = scene.polygons[i];
    Vec3 qlow = q.vertices[0], qhigh = q.vertices[0];
    for (const Vec3& v : q.vertices) qlow = qlow.cwiseMin(v), qhigh = qhigh.cwiseMax(v);
    if ((qlow.array() > high.array() + pad).any() || (qhigh.array() < low.array() - pad).any())
      continue;
    Vec3 a, b;
    if (!meeting_segment(q, frame.origin, p.normal, pad, &a, &b)) continue;
    const Segment s{frame.to_2d(a), frame.to_2d(b)};
    double inside = 0;
    for (const Piece& piece : pieces) inside = std::max(inside, inside_length(s, piece, pad));
    if (inside > 1e3 * pad) segments.push_back({(s.b - s.a).norm(), s});
  }
  std::stable_sort(segments.begin(), segments.end(),
                   [](const auto& x, const auto& y) { return x.first > y.first; });
  if (segments.empty()) return {};
  if (segments.size() > static_cast<size_t>(max_cuts)) segments.resize(max_cuts);

  for (const auto& [length, s] : segments) {
    std::vector<Piece> next;
    for (const Piece& piece : pieces) {
      if (inside_length(s, piece, 1e3 * pad) > 0) {
        for (Piece& half : cut(piece, s, pad)) next.push_back(std::move(half));
      } else {
        next.push_back(piece);
      }
    }
    pieces = std::move(next);
  }

  std::vector<std::vector<Vec3>> out;
  for (const Piece& piece : pieces) {
    std::vector<Vec3> corners;
    for (const Vec2& x : without_straight_corners(piece, pad)) corners.push_back(frame.to_3d(x));
    out.push_back(std::move(corners));
  }
  return out;
}

}  // namespace rad
