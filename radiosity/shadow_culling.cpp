#include "radiosity/shadow_culling.h"

#include <cmath>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/shaft.h"

namespace rad {

namespace {

BoxTree<3> polygon_boxes(const Scene& scene) {
  std::vector<Eigen::AlignedBox3d> boxes;
  for (const Polygon& p : scene.polygons) {
    Eigen::AlignedBox3d box;
    for (const Vec3& v : p.vertices) box.extend(v);
    boxes.push_back(box);
  }
  return BoxTree<3>(std::move(boxes));
}

}  // namespace

ShadowCulling::ShadowCulling(const Scene& scene, double pad)
    : scene_(scene),
      boxes_(polygon_boxes(scene)),
      pad_(pad),
      in_plane_(scene.tolerance().in_plane) {}

bool ShadowCulling::may_be_hidden(const Vec3& x, int receiver, const std::vector<Vec3>& corners,
                                  int shooter, const std::function<bool()>& on_the_way) const {
  // The shaft's box (Shaft's hull box): a polygon whose box misses it misses the shaft, and
  // the test is cheaper than the plane test and far cheaper than building the shaft.
  Eigen::AlignedBox3d corner_box;
  for (const Vec3& c : corners) corner_box.extend(c);
  Eigen::AlignedBox3d hull = corner_box;
  hull.min().array() -= pad_;
  hull.max().array() += pad_;
  hull.extend(x);
  std::optional<Shaft> shaft;  // built only for a polygon in its box that no plane separates
  // Whether the answer is true does not depend on the order the polygons are looked at in.
  return boxes_.any_of(hull, [&](int p) {
    if (p == receiver || p == shooter) return false;
    const Polygon& polygon = scene_.polygons[p];
    const Vec3& origin = polygon.vertices.front();
    // x and every corner strictly on one side: no segment between them meets the plane.
    const double side = polygon.normal.dot(x - origin);
    bool one_side = std::abs(side) > pad_;
    // Or one end in the plane and the other end strictly off it: a segment meets the plane
    // at its end alone (within in_plane / pad of its length of it, far inside the rays'
    // offset, where a shadow ray counts no hit). The case of a tessellated floor: its
    // triangles are all in the plane of a patch of the floor, and every pair asked the shaft
    // about each triangle between the two ends.
    bool ends_in_plane = true;
    for (size_t i = 0; i < corners.size(); ++i) {
      const double s = polygon.normal.dot(corners[i] - origin);
      one_side = one_side && std::abs(s) > pad_ && (s > 0) == (side > 0);
      ends_in_plane = ends_in_plane && std::abs(s) <= in_plane_;
    }
    if (one_side || (ends_in_plane && std::abs(side) > pad_)) return false;
    if (std::abs(side) <= in_plane_) {  // x in the plane: the corners all off it, one side
      const bool first_above = polygon.normal.dot(corners.front() - origin) > 0;
      bool corners_off = true;
      for (size_t i = 0; i < corners.size() && corners_off; ++i) {
        const double s = polygon.normal.dot(corners[i] - origin);
        corners_off = std::abs(s) > pad_ && (s > 0) == first_above;
      }
      if (corners_off) return false;
    }
    if (!shaft) {
      if (on_the_way && on_the_way()) return true;
      shaft.emplace(x, corner_box, pad_);
    }
    return shaft->may_meet(polygon.vertices, boxes_.box(p));
  });
}

}  // namespace rad
