#pragma once
/// Glossy transfer (paper 003): the light of point sources reflected by glossy surfaces onto a
/// diffuse receiver (paths L G D), by backward polygon beams (geometry/glossy_beam.h), found
/// through a hierarchy of bounding cones. A heuristic: the local pass keeps it apart from the
/// certified part (LocalPassResult::glossy).
///
/// Sources: the scene's point lights, and its emitting polygons split into point sources (003
/// §4 works from point lights: "polygon sources: split into point lights"): each triangle of an
/// emitter into light_split^2 similar pieces, each a point at its centroid radiating
/// (M / pi) area cos(angle from the emitter's normal) toward each scatterer piece.
/// Scatterers: each glossy polygon's triangles (a glossy mirror's from its front, a roughened
/// pane's from either side, through it) (fan of its convex pieces; vertex normals of a
/// smooth mesh interpolated), each split into glossy_split^2 similar pieces: the model is good
/// when a piece subtends a small angle against sigma (tests/geometry/glossy_beam_test.cpp), so
/// the split is the accuracy knob. One beam per (source, scatterer piece) whose piece's
/// centroid the source sees (first-order visibility, through filters). Beyond the paper (003
/// §4.5 leaves them out): second-order shadows, what lies between a piece's centre and the
/// receiver, asked once per piece and receiver (through filters), so that a block between a
/// glossy pane and the floor shadows its light.
///
/// The hierarchy (003 §4.3's "hierarchical traversal similar to the cone hierarchy of Chuang
/// and Cheng"): a binary tree over the beams, each node a bounding sphere (centre c, radius r)
/// of its pieces and a cone of directions (axis a, half-angle alpha) holding every scattered
/// direction of its beams widened by cutoff sigma. A receiver x off the sphere is skipped with
/// the whole node when angle(x - c, a) > alpha + asin(r / |x - c|): then for every point P of
/// every piece and every centre direction d(P) of its lobe, the scatter angle between x - P and
/// d(P) exceeds cutoff sigma (the angle between x - P and x - c is at most asin(r / |x - c|),
/// and d(P) lies within the cone's alpha, less the widening, of a), where the lobe is below
/// exp(-cutoff^2 / 2) of its peak. So the cut drops what the lobe sends beyond cutoff sigma (at
/// the default 5, 4e-6 of the peak): a second approximation, measured, never a certified one.
#include <memory>
#include <vector>

#include "geometry/glossy_beam.h"
#include "scene/ray_caster.h"
#include "scene/scene.h"

namespace rad {

struct GlossySettings {
  int split = 8;          ///< Each scatterer triangle into split^2 pieces
  int light_split = 2;    ///< Each emitter triangle into light_split^2 point sources
  double cutoff = 5;      ///< The cones' widening in sigmas (infinite: no cut)
  bool hierarchy = true;  ///< false: every beam at every receiver (the same values)
  bool shadows = true;    ///< Second-order shadows (false: 003's model as printed)
};

class GlossyTransfer {
 public:
  GlossyTransfer(const Scene& scene, const GlossySettings& settings);
  ~GlossyTransfer();

  /// True when the scene has glossy surfaces and sources to light them.
  bool empty() const { return beams_.empty(); }
  int beam_count() const { return static_cast<int>(beams_.size()); }
  const std::vector<GlossyBeam>& beams() const { return beams_; }

  struct Result {
    Rgb irradiance = Rgb::Zero();
    int beams = 0;  ///< Beams evaluated (after the hierarchy's cut)
  };
  /// The glossy irradiance at x with unit normal n. Thread-safe.
  Result irradiance(const Vec3& x, const Vec3& n) const;

 private:
  struct Node {
    Vec3 centre, axis;
    double radius = 0, half_angle = 0;
    int first = 0, count = 0;  ///< Its beams, [first, first + count) of order_
    int left = -1, right = -1;
  };
  int build(int first, int count);
  /// Whether the node may light x.
  bool may_reach(const Node& node, const Vec3& x) const;

  std::vector<GlossyBeam> beams_;
  std::vector<int> beam_piece_;        ///< Each beam's scatterer piece
  std::vector<Vec3> piece_centre_;     ///< Each piece's centre
  std::vector<Vec3> piece_normal_;     ///< Each piece's face normal
  std::unique_ptr<RayCaster> caster_;  ///< Second-order shadows; null without
  double offset_ = 0;
  std::vector<int> order_;
  std::vector<Node> nodes_;
  std::vector<Vec3> beam_centre_;  ///< Centroid of each beam's piece
  std::vector<Node> leaf_bounds_;  ///< Each beam's own sphere and cone
  bool hierarchy_ = true;
};

}  // namespace rad
