#pragma once
/// The polygons a point may see: per-pixel work only for what the pixel can see (issue 36's
/// second target), by a conservative visibility walk of a box tree over the scene's polygons.
///
/// From x, the tree is walked nearest first (geometry/box_tree.h, nearest_first); each polygon
/// reached is kept and, when opaque, inserted into the visible-surface structure of x
/// (hemisphere/blocker_surface.h); a node of the tree is opened only when its box may show
/// above x's horizon past what is inserted so far. Behind a room's walls, whole storeys are
/// then passed over at the cost of a few box tests.
///
/// Why it leaves out nothing that matters (proof). A node is passed over only when x lies
/// outside its box (grown by twice the pad) and every face of the box (grown by the pad) that x
/// is outside of lies more than the pad from x (never edge-on to the query) and has visible
/// form factor 0 against the inserted polygons: each direction above
/// the horizon that enters it meets an inserted opaque polygon strictly nearer first (the query
/// counts ties and coplanar cells as visible: the face asks with the lowest id). A ray from x
/// into the box enters through such a face, so along every direction above the horizon that
/// reaches anything in the box, an inserted opaque polygon O lies nearer than it. For a polygon
/// P left out, then:
///  - P's contribution to H(x) is 0: nothing of it is visible above the horizon;
///  - P hides nothing that is visible: where P is nearer than another polygon R, O is nearer
///    still, so that part of R is hidden by O whether P counts or not; and O, kept and nearer
///    than part of R, passes the shaft culling as R's blocker (localpass/occlusion_culling.h
///    keeps every polygon that hides part of R).
/// So the local pass over the kept polygons alone (as roots of the sum and as candidate
/// blockers) computes the same terms with the same certified intervals. Filters (000 §2.2) are
/// kept but not inserted: light passes them. Inserting fewer polygons only opens more nodes.
#include <Eigen/Geometry>
#include <vector>

#include "geometry/box_tree.h"
#include "geometry/emitting_face.h"
#include "geometry/tolerance.h"
#include "scene/scene.h"

namespace rad {

class VisibleSet {
 public:
  /// `pieces[p]`: polygon p as convex pieces (faces_from_polygons), as the local pass's
  /// visibility queries use them; referenced, not copied.
  VisibleSet(const Scene& scene, const std::vector<std::vector<EmittingFace>>& pieces);

  /// The polygons x (unit normal n) may see, ascending. Thread-safe.
  std::vector<int> polygons(const Vec3& x, const Vec3& n) const;

 private:
  const std::vector<std::vector<EmittingFace>>& pieces_;
  std::vector<char> opaque_;  ///< Per polygon: 1 when it hides what lies behind it
  BoxTree<3> tree_;           ///< Over the polygons' boxes
  Tolerance tolerance_;
};

}  // namespace rad
