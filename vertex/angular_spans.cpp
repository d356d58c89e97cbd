#include "vertex/angular_spans.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "geometry/tolerance.h"
#include "vertex/vertex_formula.h"

namespace rad {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

/// Angle in [0, 2 pi) from `from` to `to`, counter-clockwise.
double ccw_angle(double from, double to) {
  double a = to - from;
  while (a < 0) a += kTwoPi;
  while (a >= kTwoPi) a -= kTwoPi;
  return a;
}

struct Boundary {
  double angle;  ///< Of its image direction, in (-pi, pi]
  Vec3 plane;    ///< Through x, containing the boundary
};

/// The equal-depth plane of two polygons (unit), or zero when they are coplanar.
Vec3 equal_depth_plane(const SpanEntry& a, const SpanEntry& b) {
  const Vec3 m = a.offset * b.normal - b.offset * a.normal;
  const double length = m.norm();
  return length > relative::kRounding * (std::abs(a.offset) + std::abs(b.offset)) ? Vec3(m / length)
                                                                                  : Vec3::Zero();
}

/// k . (q, 1): where q lies relative to the image line of plane k (times |k_xy|), zero when
/// within its rounding (a line through q up to rounding is taken through q).
double line_value(const Vec3& k, const Vec2& q) {
  const double f = k.x() * q.x() + k.y() * q.y() + k.z();
  const double rounding =
      8e-16 * (std::abs(k.x() * q.x()) + std::abs(k.y() * q.y()) + std::abs(k.z()));
  return std::abs(f) <= rounding ? 0.0 : f;
}

/// Whether a is nearer than b in the sector whose middle meets the circle of radius `circle`
/// around q in image direction w.
bool nearer(const SpanEntry& a, const SpanEntry& b, const Vec3& d, const Vec2& q, const Vec2& w,
            double radius, double circle) {
  const Vec3 m = equal_depth_plane(a, b);
  if (m == Vec3::Zero()) return a.order < b.order;  // equally deep everywhere
  // Depth t = c / (n . d') > 0, so sign(n . d') = sign(c): a is nearer where
  // sign(c_a c_b) (m . d') < 0 (multiply t_a < t_b by (n_a . d')(n_b . d')). Where they meet in
  // the cone, the side is taken at the sector's point on the circle, where the boundaries were
  // ordered: the line of m need not pass through q.
  const double sign = (a.offset > 0) == (b.offset > 0) ? 1.0 : -1.0;
  if (relative_line_distance(m, q) < radius) {
    return sign * (line_value(m, q) + circle * (m.x() * w.x() + m.y() * w.y())) < 0;
  }
  return a.offset / a.normal.dot(d) < b.offset / b.normal.dot(d);
}

}  // namespace

double relative_line_distance(const Vec3& k, const Vec2& q) {
  const double along = std::hypot(k.x(), k.y());
  if (!(along > 0)) return std::numeric_limits<double>::infinity();  // the horizon's own plane
  return std::abs(k.x() * q.x() + k.y() * q.y() + k.z()) / (along * (1 + q.norm()));
}

Rgb angular_span_sum(const Vec3& d, std::span<const SpanEntry> entries, double radius) {
  if (entries.empty()) return Rgb::Zero();
  const Vec2 q(d.x() / d.z(), d.y() / d.z());
  // A boundary is ordered by where it crosses a circle around q somewhat wider than the cone,
  // not by its direction alone: a line snapped from within the cone may pass beside q, and two
  // such lines can share a direction yet be different planes with different G (a vertex on the
  // receiver's tangent plane: its two cut points on the image square fall in one cone, and the
  // edges leaving it are nearly parallel in the image).
  const double circle = 2 * radius * (1 + q.norm());
  const auto angle_of = [&](const Vec3& k, double sense) {
    const Vec2 w = sense * Vec2(k.y(), -k.x());
    const Vec2 offset = -line_value(k, q) * k.head<2>() / k.head<2>().squaredNorm();
    const Vec2 exit =
        offset + std::sqrt(std::max(circle * circle - offset.squaredNorm(), 0.0)) * w.normalized();
    return std::atan2(exit.y(), exit.x());
  };

  std::vector<Boundary> boundaries;
  std::vector<double> start(entries.size()), width(entries.size());
  for (size_t i = 0; i < entries.size(); ++i) {
    const SpanEntry& s = entries[i];
    if (s.kind == SpanEntry::Kind::full) {
      width[i] = kTwoPi;
      continue;
    }
    start[i] = angle_of(s.start, 1);
    boundaries.push_back({start[i], s.start});
    const Vec3& end_plane = s.kind == SpanEntry::Kind::edge ? s.start : s.end;
    const double end = angle_of(end_plane, -1);
    width[i] = ccw_angle(start[i], end);
    boundaries.push_back({end, end_plane});
  }
  // Where two polygons meet on the ray, the line where they are equally deep is a boundary too.
  for (size_t i = 0; i < entries.size(); ++i) {
    for (size_t j = i + 1; j < entries.size(); ++j) {
      const Vec3 m = equal_depth_plane(entries[i], entries[j]);
      if (m == Vec3::Zero() || !(relative_line_distance(m, q) < radius)) continue;
      boundaries.push_back({angle_of(m, 1), m});
      boundaries.push_back({angle_of(m, -1), m});
    }
  }
  if (boundaries.empty()) return Rgb::Zero();
  std::sort(boundaries.begin(), boundaries.end(),
            [](const Boundary& a, const Boundary& b) { return a.angle < b.angle; });
  const size_t count = boundaries.size();
  const auto gap_after = [&](size_t b) {
    return b + 1 < count ? boundaries[b + 1].angle - boundaries[b].angle
                         : boundaries[0].angle + kTwoPi - boundaries[b].angle;
  };

  // The emission seen in the sector counter-clockwise after each boundary (up to the next one).
  bool filters = false;
  for (const SpanEntry& s : entries) filters = filters || s.transmittance != Rgb::Zero();
  std::vector<Rgb> seen(count, Rgb::Zero());
  std::vector<int> covering;  // the entries over a sector, front to back
  for (size_t b = 0; b < count; ++b) {
    const double gap = gap_after(b);
    if (!(gap > 0)) continue;  // coincident boundaries: an empty sector, never read
    const double mid = boundaries[b].angle + 0.5 * gap;
    const Vec2 w(std::cos(mid), std::sin(mid));
    const auto in_front = [&](int i, int j) {
      return nearer(entries[i], entries[j], d, q, w, radius, circle);
    };
    if (!filters) {
      int front = -1;
      for (size_t i = 0; i < entries.size(); ++i) {
        if (!(ccw_angle(start[i], mid) < width[i])) continue;
        if (front < 0 || in_front(static_cast<int>(i), front)) front = static_cast<int>(i);
      }
      if (front >= 0) seen[b] = entries[front].exitance;
      continue;
    }
    // Filters (000 §2.2): everything over the sector in depth order, composed front to back.
    // Insertion sort: a handful of entries, and it needs no strict weak order from `nearer`.
    covering.clear();
    for (size_t i = 0; i < entries.size(); ++i) {
      if (!(ccw_angle(start[i], mid) < width[i])) continue;
      covering.push_back(static_cast<int>(i));
      for (size_t k = covering.size() - 1; k > 0 && in_front(covering[k], covering[k - 1]); --k)
        std::swap(covering[k], covering[k - 1]);
    }
    Rgb passed = Rgb::Ones();  // product of the transmittances in front
    for (const int i : covering) {
      seen[b] += passed.cwiseProduct(entries[i].exitance);
      passed = passed.cwiseProduct(entries[i].transmittance);
      if (passed == Rgb::Zero()) break;  // an opaque entry ends the line of sight
    }
  }

  // Sum (M_after - M_before) G over groups of coincident boundaries, starting after a sector
  // with width so that every group has a well-defined "before".
  size_t first = 0;
  while (first < count && !(gap_after(first) > 0)) ++first;
  if (first == count) return Rgb::Zero();
  Rgb sum = Rgb::Zero();
  Rgb before = seen[first];
  for (size_t step = 1; step <= count; ++step) {
    const size_t b = (first + step) % count;
    if (!(gap_after(b) > 0)) continue;  // more boundaries at this angle follow
    const Rgb& after = seen[b];
    if (after != before) sum += (after - before) * stark_G(q.x(), q.y(), boundaries[b].plane);
    before = after;
  }
  return sum;
}

}  // namespace rad
