#pragma once
/// Exact irradiance at a point by hemisphere projection (paper 004 §3; DESIGN.md §4).
#include <memory>
#include <vector>

#include "localpass/emitting_faces.h"
#include "scene/scene.h"

namespace rad {

/// One visible piece of a polygon, as seen from the gather point.
struct VisibleFragment {
  int polygon = -1;           ///< Index into Scene::polygons.
  double form_factor = 0;     ///< Its form factor for the receiver.
  bool front_facing = false;  ///< True when the receiver sees the polygon's front (it may emit).
  std::vector<Vec3> directions;  ///< Unit vertex directions from the point (convex, in order).
};

/// What a gather found.
struct GatherResult {
  Rgb irradiance = Rgb::Zero();  ///< H(x) [W/m^2]: sum of visible form factors x exitance.
  double covered = 0;            ///< Sum of all visible form factors (<= 1; 1 when enclosed).
  std::vector<VisibleFragment> fragments;  ///< Filled when asked for.
};

/// Exact irradiance from a scene's polygons at points with normals. Every polygon occludes from
/// both sides; a polygon radiates its exitance from its front side only. Nothing is sampled:
/// the visible part of every polygon is computed exactly (hemisphere/visible_surface.h) and its
/// form factor by Lambert's contour formula.
///
/// Degenerate input is defined, not special-cased: a polygon whose plane contains x (x on it,
/// on its edge or vertex, or seen edge-on) subtends no solid angle and is skipped; parts below
/// x's tangent plane are clipped away in 3D before projection.
class HemisphereGatherer {
 public:
  /// Exitance per polygon: the materials' emission (direct lighting only).
  explicit HemisphereGatherer(const Scene& scene);
  /// Exitance per polygon given; #exitance == #polygons.
  HemisphereGatherer(const Scene& scene, std::vector<Rgb> exitance);
  /// Any faces (e.g. faces_from_solution: every element radiates its radiosity).
  HemisphereGatherer(const Scene& scene, std::vector<EmittingFace> faces);

  /// Irradiance at x (on or off a surface) for the unit receiver normal n. Thread-safe.
  /// Cost: O(P log P) to order the P convex pieces, then one BSP insertion per piece above the
  /// horizon (measured in bench/results/hemisphere.md).
  GatherResult gather(const Vec3& x, const Vec3& n, bool keep_fragments = false) const;
  int face_count() const { return static_cast<int>(faces_.size()); }

  /// Incremental gathering at one point (the local pass): faces are projected as they are
  /// added, each once, in any order (the visible surface does not depend on it); the result at
  /// any time counts the visible parts of the added faces marked radiating. Those parts are
  /// final once every face that may hide them has been added.
  class Session {
   public:
    Session(const HemisphereGatherer& gatherer, const Vec3& x, const Vec3& n);
    /// Projects these faces (those already added are skipped), nearest first.
    void add(const std::vector<int>& faces);
    int added() const { return added_count_; }
    /// Irradiance from the added faces flagged in `radiating` (one flag per face), and the
    /// form factor they cover.
    Rgb irradiance(const std::vector<char>& radiating, double* covered) const;

   private:
    const HemisphereGatherer& gatherer_;
    Vec3 x_, n_;
    std::vector<char> added_;
    int added_count_ = 0;
    std::shared_ptr<void> visible_;  ///< hemi::VisibleSurface (kept out of this header)
  };

 private:
  /// Projects face k into `visible` if it has solid angle above x's horizon.
  void project(int k, const Vec3& x, const Vec3& n, void* visible) const;

  const Scene& scene_;
  std::vector<EmittingFace> faces_;
  std::vector<Vec3> centres_;     ///< Per face: centre of its bounding sphere...
  std::vector<double> radii_;     ///< ...and its radius.
  double in_plane_ = 0;  ///< |plane offset| below this: x is in the polygon's plane
};

}  // namespace rad
