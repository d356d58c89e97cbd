#include "localpass/visible_set.h"

#include <algorithm>
#include <limits>

#include "hemisphere/blocker_surface.h"
#include "scene/polygon.h"

namespace rad {
namespace {

/// Whether nothing in `box` can show above x's horizon past what `surface` holds (the proof is
/// in the header): x outside the box grown by 2 pad, and every face of the box grown by pad that
/// x is outside of lies more than pad from x (so that the query never takes it for edge-on,
/// as it does within the gatherers' in-plane tolerance) and has visible form factor 0, asked
/// with the lowest id (so that it shows in cells of polygons in its own plane).
bool hidden(const BlockerSurface& surface, const Eigen::AlignedBox3d& box, const Vec3& x,
            double pad) {
  if (surface.empty()) return false;
  Eigen::AlignedBox3d outer = box;
  outer.min().array() -= 2 * pad;
  outer.max().array() += 2 * pad;
  if (outer.contains(x)) return false;
  Eigen::AlignedBox3d grown = box;
  grown.min().array() -= pad;
  grown.max().array() += pad;
  const Vec3 lo = grown.min(), hi = grown.max();
  for (int a = 0; a < 3; ++a) {
    for (const int side : {-1, 1}) {
      const double at = side < 0 ? lo[a] : hi[a];
      const double beyond = side < 0 ? at - x[a] : x[a] - at;  // x's height over the face
      if (!(beyond > 0)) continue;                             // x does not see this face
      if (!(beyond > pad)) return false;  // nearly in its plane: not asked, not proven hidden
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      std::vector<Vec3> face(4);
      for (int k = 0; k < 4; ++k) {
        face[k][a] = at;
        face[k][b] = (k == 1 || k == 2) ? hi[b] : lo[b];
        face[k][c] = k >= 2 ? hi[c] : lo[c];
      }
      const Vec3 normal = side * Vec3::Unit(a);
      if (surface.visible_form_factor(std::numeric_limits<int>::min(), face, normal) > 0)
        return false;
    }
  }
  return true;
}

}  // namespace

VisibleSet::VisibleSet(const Scene& scene, const std::vector<std::vector<EmittingFace>>& pieces)
    : pieces_(pieces), tolerance_(scene.tolerance()) {
  std::vector<Eigen::AlignedBox3d> boxes;
  boxes.reserve(scene.polygons.size());
  opaque_.reserve(scene.polygons.size());
  for (const Polygon& polygon : scene.polygons) {
    boxes.push_back(bounding_box(polygon.vertices));
    opaque_.push_back(!scene.materials[polygon.material].is_filter());
  }
  tree_ = BoxTree<3>(std::move(boxes));
}

std::vector<int> VisibleSet::polygons(const Vec3& x, const Vec3& n) const {
  BlockerSurface surface(x, n, tolerance_);
  std::vector<int> kept;
  const double pad = tolerance_.pad;
  tree_.nearest_first(
      x, [&](const Eigen::AlignedBox3d& box) { return !hidden(surface, box, x, pad); },
      [&](int p) {
        if (hidden(surface, tree_.box(p), x, pad)) return;
        kept.push_back(p);
        if (!opaque_[p]) return;
        for (const EmittingFace& piece : pieces_[p]) surface.add(p, piece.vertices, piece.normal);
      });
  std::ranges::sort(kept);
  return kept;
}

}  // namespace rad
