#pragma once
/// The error-bounded local pass (paper 004 §4.3, Fig. 6; DESIGN.md §3 eqs. 7-10): at a point,
/// gather exactly from the solution's elements in order of decreasing bound, and stop as soon as
/// what may remain is below the tolerance, with a certified bound on the error.
///
/// First the faces are split (localpass/occlusion_culling.h): those nothing can hide from x
/// contribute B(A) FF(x, A above the horizon) exactly, by Lambert's formula, with no
/// visibility work; the others, by leaf voxel, go to an exact gatherer together with the faces
/// that may hide them (004's SolveVisibility, made exact by shafts).
///
/// Why the bound is certified. A gather lets only the selected faces radiate and sees every
/// face that may hide them, so it returns exactly
///   H_S = sum over selected faces A of B(A) FF(x, visible part of A),
/// and H = H_S + sum over the other faces of the same terms, each >= 0. An unselected face's
/// term is at most its unoccluded one, U(A) = B(A) FF(x, A above the horizon), computed for the
/// ordering anyway (it replaces eq. 8's box bound: tighter, and as certain). Hence
///   0 <= H - H_S <= R = sum over unselected faces of U(A),
/// per channel. A gatherer that reports coverage (the hemisphere's) also gives the form factor C
/// covered by the visible parts of the unoccluded and the selected faces; the unselected faces can
/// only show outside them, so
///   H - H_S <= (largest unselected radiosity toward x) * (1 - C),
/// the certified form of 004's eq. 10, and R is the smaller of the two. The error has one sign.
/// The pass reports H_S + R/2 with the bound R/2, and stops when
///   max_c R_c / 2 <= tolerance * max_c (H_S + R/2)_c,
/// so the relative error (against the brightest channel) is at most the tolerance.
#include <memory>
#include <vector>

#include "geometry/emitting_face.h"
#include "geometry/exact_gatherer.h"
#include "geometry/tolerance.h"
#include "localpass/cluster_tree.h"
#include "localpass/method.h"
#include "localpass/occlusion_culling.h"
#include "octree/octree.h"
#include "scene/scene.h"

namespace rad {

struct LocalPassSettings {
  OctreeSettings octree;
  /// false: no shaft culling; every face that can light x goes to the gatherer at once with
  /// every face as an occluder (the naive exact gather, the baseline for measuring the culling;
  /// the same values at tolerance 0).
  bool occlusion_culling = true;
};

struct LocalPassResult {
  /// H(x) estimate [W/m^2]: the exact part plus half the remainder bound.
  Rgb irradiance = Rgb::Zero();
  Rgb bound = Rgb::Zero();   ///< Certified: |H(x) - irradiance| <= bound, per channel
  int gathered_exactly = 0;  ///< Faces gathered exactly (unoccluded or radiating in a gather)
  int unoccluded = 0;        ///< Of those, faces nothing can hide (Lambert's formula alone)
  int projected = 0;         ///< Faces projected (hemisphere: selected + possible occluders;
                             ///< vertex tracing: the same, summed over its traces)
  int clusters = 0;          ///< Cluster intervals computed (one Lambert formula each)
  int gathers = 0;           ///< Exact gathers run (0 when nothing can light x)
};

/// The octree's items: one per face, with its polygon's normal and its exitance.
std::vector<OctreeItem> octree_items(const std::vector<EmittingFace>& faces);

class LocalPass {
 public:
  /// `faces` are typically faces_from_solution (every element radiates its radiosity);
  /// `method` picks the exact gatherer (hemisphere or vertex; Error for Monte Carlo).
  LocalPass(const Scene& scene, std::vector<EmittingFace> faces, Method method,
            const LocalPassSettings& settings = {});

  /// Irradiance at x for unit normal n, to the given relative tolerance (0: exact, every face
  /// that may be hidden radiating in one gather). Thread-safe.
  LocalPassResult gather(const Vec3& x, const Vec3& n, double tolerance) const;

  const Octree& octree() const { return octree_; }
  int face_count() const { return static_cast<int>(faces_.size()); }

 private:
  LocalPassResult gather_by_clusters(const Vec3& x, const Vec3& n, double tolerance) const;
  /// No culling: every face that can light x radiates in one gather, every face may hide it.
  LocalPassResult gather_plainly(const Vec3& x, const Vec3& n) const;

  std::vector<EmittingFace> faces_;
  /// The scene's polygons as convex pieces, by polygon: the blockers of the visibility queries
  /// (hemisphere/blocker_surface.h) that bound partly hidden clusters.
  std::vector<std::vector<EmittingFace>> blocker_pieces_;
  Tolerance tolerance_;
  /// Hemisphere: partly hidden faces are queried too (the query is that method's projection).
  /// Vertex tracing gathers them in steps of its own session.
  bool faces_by_query_;
  bool occlusion_culling_;
  Octree octree_;
  std::unique_ptr<ExactGatherer> gatherer_;
  OcclusionCulling culling_;
  ClusterTree clusters_;
};

}  // namespace rad
