#pragma once
/// Exact irradiance at a point by hemisphere projection (paper 004 §3; DESIGN.md §4): every face
/// above x's horizon is projected onto the unit hemisphere, the visible parts are found front to
/// back (hemisphere/visible_surface.h), and each visible part's form factor is Lambert's
/// formula on its vertices (geometry/lambert.h).
#include <memory>
#include <vector>

#include "geometry/emitting_face.h"
#include "geometry/exact_gatherer.h"
#include "geometry/tolerance.h"

namespace rad {

/// One visible piece of a face, as seen from the gather point.
struct VisibleFragment {
  int polygon = -1;              ///< The face's polygon.
  double form_factor = 0;        ///< Its form factor for the receiver.
  bool front_facing = false;     ///< True when the receiver sees the polygon's front (it may emit).
  std::vector<Vec3> directions;  ///< Unit vertex directions from the point (convex, in order).
};

/// What a whole gather found.
struct HemisphereGather {
  Rgb irradiance = Rgb::Zero();  ///< H(x) [W/m^2]: sum of visible form factors x exitance.
  double covered = 0;            ///< Sum of all visible form factors (<= 1; 1 when enclosed).
  std::vector<VisibleFragment> fragments;  ///< Filled when asked for.
};

/// Exact irradiance from faces at points with normals. Every face occludes from both sides;
/// a face radiates its exitance from its front side only. Nothing is sampled.
///
/// Degenerate input is defined, not special-cased: a face whose plane contains x (x on it, on
/// its edge or vertex, or seen edge-on; Tolerance::in_plane) subtends no solid angle and is
/// skipped; parts below x's tangent plane are clipped away in 3D before projection.
class HemisphereGatherer final : public ExactGatherer {
 public:
  /// `tolerance`: the scene's (Scene::tolerance()), the same the local pass's culling uses.
  /// Throws std::invalid_argument for a face with fewer than 3 vertices.
  HemisphereGatherer(std::vector<EmittingFace> faces, const Tolerance& tolerance);

  /// Everything at once, optionally with the visible fragments. Thread-safe.
  /// Cost: O(P log P) to order the P faces, then one BSP insertion per face above the horizon
  /// (measured in bench/results/hemisphere.md).
  HemisphereGather gather(const Vec3& x, const Vec3& n, bool keep_fragments = false) const;

  /// Incremental gathering at one point (ExactGatherSession): faces are projected as they are
  /// added, each once, in any order (the visible surface does not depend on it); the total
  /// counts the visible parts of the faces radiated so far. Those parts are final once every
  /// face that may hide them has been added.
  std::unique_ptr<ExactGatherSession> start(const Vec3& x, const Vec3& n) const override;
  bool incremental() const override { return true; }
  bool reports_coverage() const override { return true; }
  int face_count() const override { return static_cast<int>(faces_.size()); }

 private:
  class Session;
  /// A lower bound on the distance from x to face k: projecting nearest first lets far faces
  /// stop at their first depth test. The order never changes the result, only the work.
  double distance_bound(int k, const Vec3& x) const;
  /// Projects face k into `visible` if it has solid angle above x's horizon.
  void project(int k, const Vec3& x, const Vec3& n, void* visible) const;

  std::vector<EmittingFace> faces_;
  std::vector<Vec3> centres_;  ///< Per face: centre of its bounding sphere...
  std::vector<double> radii_;  ///< ...and its radius.
  double in_plane_ = 0;        ///< Tolerance::in_plane
};

}  // namespace rad
