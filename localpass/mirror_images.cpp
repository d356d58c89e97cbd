#include "localpass/mirror_images.h"

#include <algorithm>
#include <cmath>

#include "scene/polygon.h"
#include "scene/polygon_faces.h"

namespace rad {
namespace {

/// The front half-space of a mirror piece: where it reflects.
HalfSpace front_of(const MirrorPiece& m) { return {m.normal, m.offset}; }

/// Convex hull of 2D points (Andrew's monotone chain), counter-clockwise.
std::vector<Vec2> convex_hull(std::vector<Vec2> points) {
  std::sort(points.begin(), points.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() != b.x() ? a.x() < b.x() : a.y() < b.y();
  });
  const auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Vec2> hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], points[i - 1]) <= 0) --k;
    hull[k++] = points[i - 1];
  }
  hull.resize(k > 1 ? k - 1 : k);
  return hull;
}

/// True when some edge normal of either convex polygon separates them by more than `margin`.
bool separated(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double margin) {
  const auto separates = [&](const std::vector<Vec2>& p, const std::vector<Vec2>& q) {
    for (size_t i = 0; i < p.size(); ++i) {
      const Vec2 e = p[(i + 1) % p.size()] - p[i];
      const Vec2 outward(e.y(), -e.x());  // p counter-clockwise: its outside is to the right
      const double length = outward.norm();
      if (!(length > 0)) continue;
      const double edge = outward.dot(p[i]) / length;
      double nearest = std::numeric_limits<double>::infinity();
      for (const Vec2& v : q) nearest = std::min(nearest, outward.dot(v) / length);
      if (nearest > edge + margin) return true;
    }
    return false;
  };
  return separates(a, b) || separates(b, a);
}

}  // namespace

UnfoldedScene unfold(const Scene& scene, const std::vector<EmittingFace>& faces,
                     const std::vector<MirrorPiece>& pieces, const std::vector<int>& chain,
                     double in_plane) {
  // Leg j (1-based, k + 1 the last) lies in front of m_(j-1) and m_j and is mapped by
  // T_j = R_k ... R_j (T_(k+1) the identity): the receiver is mapped by T_1, the last leg
  // stays where it is.
  const int k = static_cast<int>(chain.size());
  std::vector<Leg> legs(k + 1);
  std::vector<Aperture> apertures;
  Rgb specular = Rgb::Ones();
  for (int j = k; j >= 1; --j) {
    // T_j = T_(j+1) R_j, with R_j(p) = (I - 2 n n^T) p + 2 offset n.
    const MirrorPiece& m = pieces[chain[j - 1]];
    const Eigen::Matrix3d reflection =
        Eigen::Matrix3d::Identity() - 2 * m.normal * m.normal.transpose();
    const Leg& after = legs[j];
    legs[j - 1].linear = after.linear * reflection;
    legs[j - 1].translation = after.linear * (2 * m.offset * m.normal) + after.translation;
    specular = specular.cwiseProduct(m.specular);
  }
  for (int j = 1; j <= k + 1; ++j) {
    if (j >= 2) legs[j - 1].bounds.push_back(front_of(pieces[chain[j - 2]]));
    if (j <= k) legs[j - 1].bounds.push_back(front_of(pieces[chain[j - 1]]));
  }
  for (const int piece : chain) {
    const MirrorPiece& m = pieces[piece];
    apertures.push_back({m.outline, m.normal, m.polygon});
  }
  UnfoldedScene out =
      unfold_legs(scene, faces, apertures, legs, legs[0].linear, legs[0].translation, in_plane);
  out.specular = specular;
  return out;
}

Eigen::AlignedBox3d sources_in_front(const std::vector<EmittingFace>& faces,
                                     const std::vector<MirrorPiece>& pieces,
                                     const MirrorPiece& mirror, double in_plane) {
  Eigen::AlignedBox3d box;
  const std::vector<HalfSpace> front{front_of(mirror)};
  for (const EmittingFace& f : faces) {
    if (f.exitance == Rgb::Zero()) continue;
    if (const auto clipped = clipped_to(f, front, in_plane)) {
      for (const Vec3& v : clipped->vertices) box.extend(v);
    }
  }
  for (const MirrorPiece& p : pieces) {
    EmittingFace outline;
    outline.vertices = p.outline;
    outline.on_boundary.assign(p.outline.size(), true);
    outline.normal = p.normal;
    if (const auto clipped = clipped_to(outline, front, in_plane)) {
      for (const Vec3& v : clipped->vertices) box.extend(v);
    }
  }
  return box;
}

bool may_see_through(const MirrorPiece& mirror, const Vec3& x_mirrored,
                     const Eigen::AlignedBox3d& sources) {
  if (sources.isEmpty()) return false;
  const double hx = mirror.height(x_mirrored);
  if (!(hx < 0)) return true;  // not behind the plane: no claim
  const PlaneFrame frame(mirror.outline.front(), mirror.normal);
  std::vector<Vec2> projected;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p = sources.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner));
    const double hp = mirror.height(p);
    if (!(hp > 0)) return true;  // the box reaches the plane: every direction may pass
    projected.push_back(frame.to_2d(x_mirrored + (hx / (hx - hp)) * (p - x_mirrored)));
  }
  std::vector<Vec2> outline;
  for (const Vec3& v : mirror.outline) outline.push_back(frame.to_2d(v));
  const double margin = 1e-9 * (extent(mirror.outline) + (sources.max() - sources.min()).norm());
  return !separated(convex_hull(projected), outline, margin);
}

}  // namespace rad
