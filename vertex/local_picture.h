#pragma once
/// Inside vertex/: the picture of the scene around one gather point x, in the image plane one
/// unit above x (x at the origin, receiver normal +z), as vertex tracing builds it (paper 001
/// Algorithm 1, §3-§5): the faces inside the image square, their edges and the interpenetration
/// segments as features, and the candidate vertices of the visible map. vertex_tracer.cpp runs
/// the steps; this header names them and their data.
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "geometry/emitting_face.h"
#include "geometry/vec.h"
#include "vertex/image_box_tree.h"

namespace rad::vertex_detail {

/// Nape angle (radians) of the traced cones (001 §5): features within it of a traced direction
/// are snapped onto it. Snapping a feature by an angle a moves a vertex term by O(a), so the
/// error stays far below the 1e-9 the gatherers are compared at; the paper's 1e-6..1e-7 was
/// for single precision trouble we do not have. Faces smaller than the cone are skipped (they
/// subtend < pi a^2).
constexpr double kNape = 1e-10;
/// Emitter culling keeps everything within this relative distance of an emitter's box: more
/// than any cone radius used (the nape angle plus the spread of merged candidates).
constexpr double kCullMargin = 1e-6;

inline Vec2 image_of(const Vec3& d) { return {d.x() / d.z(), d.y() / d.z()}; }

/// Distance between image points relative to 1 + |q|: about the angle between the directions
/// near the zenith, and the same relative precision next to the horizon.
inline double relative_distance(const Vec2& a, const Vec2& b) {
  return (a - b).norm() / (1 + std::min(a.norm(), b.norm()));
}

/// Distance from image point q to the image segment a -> b, relative to 1 + |q| (see
/// local_picture.cpp for why it is measured in the image).
double relative_segment_distance(const Vec2& a, const Vec2& b, const Vec2& q);

/// The box of image points, padded by `radius` relative to their size.
ImageBox padded_box(const std::vector<Vec2>& points, double radius);

/// Edge flags of a LocalFace: 0 inside the polygon, 1 on its boundary, kCutBySquare + i along
/// square plane i (nonzero: a silhouette, the face ends there).
constexpr char kCutBySquare = 2;

/// A face as seen from x: local coordinates, clipped at the image square, as a loop whose
/// interior is on the k . d >= 0 side of every edge plane.
struct LocalFace {
  int face = -1;
  Vec3 normal;
  double offset = 0;
  Rgb exitance = Rgb::Zero();
  Rgb transmittance = Rgb::Zero();  ///< From either side (000 §2.2); 0: opaque.
  std::vector<Vec3> dirs;           ///< Unit vertex directions...
  std::vector<Vec2> image;          ///< ...and their images q = (d_x, d_y) / d_z.
  std::vector<Vec3>
      k;  ///< Edge i (dirs i -> i+1): unit normal of its plane through x (0: degenerate).
  std::vector<char> silhouette;  ///< Edge flag (kCutBySquare).
  int first_feature = 0;         ///< Edge i is feature first_feature + i.
  int first_vertex = 0;          ///< Vertex i is candidate vertex_candidate[first_vertex + i].
  ImageBox box;
};

/// An edge or an intersection segment: a great-circle arc a -> b of plane k (unit, a x b),
/// whose image is the segment qa -> qb.
struct Feature {
  Vec3 a, b, k;
  Vec2 qa, qb;
  int polygon = -1;  ///< -1 for intersection segments (they may cross anything)
  /// May make an apparent vertex: a polygon's outline, a cut by the square, an intersection
  /// segment. A filter's inner edges and those seen through it do cross in the picture, but
  /// add no vertex: the transmittance is the same on both sides of an inner edge, so the
  /// composed exitance M_f + T M_b steps along each line alone, and a straight step through a
  /// point contributes nothing there (001 eq. 9 is linear in M).
  bool silhouette = false;
};

/// A possible vertex of the visible map.
struct Candidate {
  Vec3 d;
  Vec2 q;
  bool intrinsic;  ///< A vertex (polygon vertex, cut by the square, or intersection end)
};

/// A segment where two polygons interpenetrate (view-independent, world coordinates).
struct Segment {
  Vec3 a, b;
  int polygon_a, polygon_b;
};

/// The local frame at x: world point -> (u, v, n) coordinates relative to x.
struct LocalFrame {
  Vec3 x, u, v, n;
  Vec3 rotate(const Vec3& r) const { return {u.dot(r), v.dot(r), n.dot(r)}; }
  Vec3 local(const Vec3& p) const { return rotate(p - x); }
};

/// Everything the steps build at one point.
struct LocalPicture {
  std::vector<LocalFace> faces;
  std::vector<ImageBox> emitter_boxes;
  std::vector<Feature> features;
  std::vector<ImageBox> feature_boxes;
  std::vector<Candidate> candidates;
  std::vector<int> vertex_candidate;           ///< LocalFace::first_vertex + i -> candidate
  std::unordered_map<uint64_t, int> crossing;  ///< pair_key(feature, feature) -> candidate
};

uint64_t pair_key(int a, int b);

/// Step 1: the faces with solid angle inside the image square, in local coordinates, and the
/// image boxes of those that radiate toward x. `emitting` (may be null): only flagged faces
/// radiate. `subset` (may be null): only these faces exist.
void add_faces_in_square(LocalPicture& picture, const LocalFrame& frame,
                         const std::vector<EmittingFace>& faces, double in_plane,
                         const std::vector<char>* emitting, const std::vector<int>* subset);

/// Only what may show in front of an emitter's image box matters (001 §4.1), box by box: the
/// emitters of a local-pass batch lie in many directions, and one box around them all would
/// keep nearly everything.
struct EmitterCulling {
  const ImageBoxTree* emitters = nullptr;
  bool enabled = true;  ///< false: keep everything (to check that culling changes nothing)
  bool near_emitter(const ImageBox& box) const { return !enabled || emitters->any(box); }
};

/// Step 2: the features, face edges then the interpenetration segments inside the square (the
/// segments' ends are intrinsic candidates). `polygon_present` (may be null): a segment counts
/// only when both its polygons have a face in the picture's subset.
void add_features(LocalPicture& picture, const LocalFrame& frame,
                  const std::vector<EmittingFace>& faces, const std::vector<Segment>& segments,
                  const std::vector<char>* polygon_present, const EmitterCulling& culling);

/// Step 3: every face vertex, and every apparent crossing of a silhouette with a feature of
/// another polygon (two edges inside opaque polygons cannot both be seen, 001 §4.2; through a
/// filter they can, but their crossing adds nothing: see Feature::silhouette).
void add_vertices_and_crossings(LocalPicture& picture);

/// Where segment p -> q crosses the plane k . d = 0 through x (see local_picture.cpp).
Vec3 cut_point(const Vec3& p, const Vec3& q, const Vec3& k);

/// The image square's planes through x (001 §3.1): k . p >= 0 keeps |u| <= L z, |v| <= L z.
const std::array<Vec3, 4>& square_planes();

}  // namespace rad::vertex_detail
