#include "vertex/interpenetration.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>

#include "scene/polygon_faces.h"

namespace rad {
namespace {

/// Clips the line p + t u to a convex polygon (counter-clockwise about `normal`, the line in its
/// plane): narrows [t0, t1]. Each edge keeps the side its inward normal n x e points to.
void clip_line(const std::vector<Vec3>& polygon, const Vec3& normal, const Vec3& p, const Vec3& u,
               double* t0, double* t1) {
  const size_t n = polygon.size();
  for (size_t i = 0; i < n && *t0 <= *t1; ++i) {
    const Vec3 inward = normal.cross(polygon[(i + 1) % n] - polygon[i]);
    const double a = inward.dot(p - polygon[i]);
    const double b = inward.dot(u);
    if (b == 0) {
      if (a < 0) *t1 = -std::numeric_limits<double>::infinity();
    } else if (b > 0) {
      *t0 = std::max(*t0, -a / b);
    } else {
      *t1 = std::min(*t1, -a / b);
    }
  }
}

}  // namespace

std::vector<Interpenetration> interpenetration_segments(const Scene& scene) {
  const auto pieces =
      faces_from_polygons(scene, std::vector<Rgb>(scene.polygons.size(), Rgb::Zero()));
  const Tolerance tolerance = scene.tolerance();
  const double pad = tolerance.pad;
  std::vector<Eigen::AlignedBox3d> boxes;
  for (const EmittingFace& f : pieces) {
    Eigen::AlignedBox3d box = bounding_box(f.vertices);
    box.min().array() -= pad;
    box.max().array() += pad;
    boxes.push_back(box);
  }
  std::vector<int> order(pieces.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return boxes[a].min().x() < boxes[b].min().x(); });

  std::vector<Interpenetration> segments;
  for (size_t oi = 0; oi < order.size(); ++oi) {
    const int i = order[oi];
    for (size_t oj = oi + 1; oj < order.size() && boxes[order[oj]].min().x() <= boxes[i].max().x();
         ++oj) {
      const int j = order[oj];
      if (pieces[i].polygon == pieces[j].polygon || !boxes[i].intersects(boxes[j])) continue;
      const Polygon& A = scene.polygons[pieces[i].polygon];
      const Polygon& B = scene.polygons[pieces[j].polygon];
      const Vec3 line = A.normal.cross(B.normal);
      const double len2 = line.squaredNorm();
      if (len2 < 1e-18) continue;  // parallel planes: apart, or coplanar (edges cross instead)
      const double da = A.normal.dot(A.vertices.front()), db = B.normal.dot(B.vertices.front());
      // The point of the line nearest the origin: n_A . p = d_A and n_B . p = d_B.
      const Vec3 p = (da * B.normal.cross(line) + db * line.cross(A.normal)) / len2;
      const Vec3 u = line / std::sqrt(len2);
      double t0 = -std::numeric_limits<double>::infinity(),
             t1 = std::numeric_limits<double>::infinity();
      clip_line(pieces[i].vertices, A.normal, p, u, &t0, &t1);
      clip_line(pieces[j].vertices, B.normal, p, u, &t0, &t1);
      if (t1 - t0 > tolerance.in_plane)
        segments.push_back({p + t0 * u, p + t1 * u, pieces[i].polygon, pieces[j].polygon});
    }
  }
  return segments;
}

}  // namespace rad
