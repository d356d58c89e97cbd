#pragma once
/// Exact irradiance by vertex tracing (paper 001 Algorithm 1, §3-§5; DESIGN.md §4): the
/// irradiance at x is a sum over the vertices of the visible map seen from x (intrinsic polygon
/// vertices, apparent crossings of edges, and, for interpenetrating polygons, the ends and
/// crossings of their intersection lines), each contributing through its angular spans
/// (localpass/angular_spans.h). No polygon is clipped against another; only against the image square
/// (the horizon).
#include <vector>

#include "localpass/emitting_faces.h"
#include "scene/scene.h"

namespace rad {

struct VertexTraceResult {
  Rgb irradiance = Rgb::Zero();  ///< H(x) [W/m^2]
  int candidates = 0;   ///< Vertices and apparent crossings found (before merging)
  int traced = 0;       ///< Cones traced: one per (possibly conjunctive) visible-map vertex
  int conjunctive = 0;  ///< Cones that merged more than one candidate
  int slow_path = 0;    ///< Merges forced by an unexpected incidence (001 §5's rigorous path)
};

class VertexTracer {
 public:
  /// Nape angle (radians) of the traced cones (001 §5): features within it of a traced
  /// direction are snapped onto it. Snapping a feature by an angle a moves a vertex term by
  /// O(a), so the error stays far below the 1e-9 the gatherers are compared at; the paper's
  /// 1e-6..1e-7 was for single precision trouble we do not have. Faces smaller than the cone
  /// are skipped (they subtend < pi a^2).
  static constexpr double kNapeAngle = 1e-10;

  struct Options {
    /// Build the local picture only where an emitter is (001 §4.1: with one or a few sources,
    /// only vertices that appear inside a source can contribute). false: everything, for
    /// checking that culling changes nothing.
    bool cull_to_emitters = true;
    /// One flag per face: only marked faces radiate, the others are black (they still
    /// occlude). Null: every face radiates its exitance.
    const std::vector<char>* emitting = nullptr;
    /// Only these faces exist: the others neither radiate nor occlude (the local pass passes
    /// the faces that may hide its radiating ones; localpass/occlusion_culling.h). Null: all.
    const std::vector<int>* faces = nullptr;
  };

  /// Direct lighting: polygons radiate their material's emission.
  explicit VertexTracer(const Scene& scene);
  /// Any faces (e.g. faces_from_solution for radiosity reconstruction, 001 §4.2).
  VertexTracer(const Scene& scene, std::vector<EmittingFace> faces);

  /// Irradiance at x for unit receiver normal n. Thread-safe.
  VertexTraceResult gather(const Vec3& x, const Vec3& n) const { return gather(x, n, Options{}); }
  VertexTraceResult gather(const Vec3& x, const Vec3& n, const Options& options) const;
  int face_count() const { return static_cast<int>(faces_.size()); }

 private:
  struct Segment {
    Vec3 a, b;
    int polygon_a, polygon_b;
  };
  const Scene& scene_;
  std::vector<EmittingFace> faces_;
  std::vector<Segment> intersections_;  ///< Where polygons interpenetrate (view-independent)
  double in_plane_ = 0;                 ///< |plane offset| below this: x is in the face's plane
};

}  // namespace rad
