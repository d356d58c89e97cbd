#pragma once
/// Exact irradiance by vertex tracing (paper 001 Algorithm 1, §3-§5; DESIGN.md §4): the
/// irradiance at x is a sum over the vertices of the visible map seen from x (intrinsic polygon
/// vertices, apparent crossings of edges, and, for interpenetrating polygons, the ends and
/// crossings of their intersection lines), each contributing through its angular spans
/// (vertex/angular_spans.h). No polygon is clipped against another; only against the image
/// square (the horizon).
#include <memory>
#include <vector>

#include "geometry/emitting_face.h"
#include "geometry/exact_gatherer.h"
#include "scene/scene.h"

namespace rad {

namespace vertex_detail {
struct Segment;
}

struct VertexTraceResult {
  Rgb irradiance = Rgb::Zero();  ///< H(x) [W/m^2]
  int candidates = 0;            ///< Vertices and apparent crossings found (before merging)
  int traced = 0;       ///< Cones traced: one per (possibly conjunctive) visible-map vertex
  int conjunctive = 0;  ///< Cones that merged more than one candidate
  int slow_path = 0;    ///< Merges forced by an unexpected incidence (001 §5's rigorous path)
};

class VertexTracer final : public ExactGatherer {
 public:
  /// Nape angle (radians) of the traced cones (001 §5; vertex/local_picture.h).
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

  /// Direct lighting: polygons radiate their material's emission (scene/polygon_faces.h).
  explicit VertexTracer(const Scene& scene);
  /// Any faces (e.g. faces_from_solution for radiosity reconstruction, 001 §4.2). Throws Error
  /// for a face that refers to no polygon of the scene or whose edge flags do not match.
  VertexTracer(const Scene& scene, std::vector<EmittingFace> faces);
  ~VertexTracer() override;

  /// Irradiance at x for unit receiver normal n. Thread-safe.
  VertexTraceResult gather(const Vec3& x, const Vec3& n) const { return gather(x, n, Options{}); }
  VertexTraceResult gather(const Vec3& x, const Vec3& n, const Options& options) const;

  /// ExactGatherSession: each step traces its radiating faces with its occluders afresh, and
  /// the session sums the steps (the faces radiate once, so nothing is counted twice).
  std::unique_ptr<ExactGatherSession> start(const Vec3& x, const Vec3& n) const override;
  bool incremental() const override { return false; }
  bool reports_coverage() const override { return false; }
  int face_count() const override { return static_cast<int>(faces_.size()); }

 private:
  class Session;
  size_t polygon_count_ = 0;
  std::vector<EmittingFace> faces_;
  std::vector<vertex_detail::Segment>
      intersections_;    ///< Where polygons interpenetrate (view-independent)
  double in_plane_ = 0;  ///< Tolerance::in_plane
};

}  // namespace rad
