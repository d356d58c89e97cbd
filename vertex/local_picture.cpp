#include "vertex/local_picture.h"

#include <algorithm>
#include <cmath>

#include "geometry/clip.h"
#include "geometry/plane.h"

namespace rad::vertex_detail {
namespace {

/// Half side of the square the image is clipped to (001 §3.1: "clip against a large bounding
/// square on the image plane"). What lies outside has a projected solid angle below
/// pi / (1 + L^2), an irradiance error below 1e-16 of the largest exitance. Clipping at a small
/// height above the tangent plane instead cuts every face along its own line (a near face at
/// 1/100 of the height's image distance of a far one), so far faces show through a band under
/// near ones that reach the tangent plane; the band's vertex terms are O(1) each, and they fail
/// to cancel. The square's four planes pass through x and are shared by every face: a face
/// that hides another up to the horizon hides it up to the square.
constexpr double kImageBound = 1e8;

/// Clips a convex loop with per-edge flags to k . p >= 0 (geometry/clip.h, crossings by
/// cut_point); the new edge along the cut gets `cut_flag`.
void clip_to_plane(std::vector<Vec3>& loop, std::vector<char>& flags, const Vec3& k,
                   char cut_flag) {
  std::vector<Vec3> out;
  std::vector<char> out_flags;
  clip_loop(
      loop, loop.size(), [&](const Vec3& p) { return k.dot(p); },
      [&](const Vec3& p, const Vec3& q, double, double) { return cut_point(p, q, k); },
      [&](const Vec3& p, int edge) {
        out.push_back(p);
        out_flags.push_back(edge == kEdgeAlongCut ? cut_flag : flags[edge]);
      });
  loop = std::move(out);
  flags = std::move(out_flags);
}

/// Where the arcs of p and q cross, if they do (ends included within the nape angle, so that a
/// crossing at a vertex is found and then merged with it).
bool arcs_cross(const Feature& p, const Feature& q, Vec3* where) {
  Vec3 c = p.k.cross(q.k);
  const double len = c.norm();
  if (!(len > 1e-14)) return false;  // the same great circle (collinear edges meet at their ends)
  c /= len;
  if (c.z() < 0) c = -c;
  if (!(c.z() > 0)) return false;  // on the horizon's great circle: outside the square
  const Vec2 image = image_of(c);
  if (!(relative_segment_distance(p.qa, p.qb, image) < kNape &&
        relative_segment_distance(q.qa, q.qb, image) < kNape)) {
    return false;
  }
  *where = c;
  return true;
}

}  // namespace

const std::array<Vec3, 4>& square_planes() {
  static const std::array<Vec3, 4> planes = {Vec3(-1, 0, kImageBound), Vec3(1, 0, kImageBound),
                                             Vec3(0, -1, kImageBound), Vec3(0, 1, kImageBound)};
  return planes;
}

// Interpolating would give the point's height as a difference of two large numbers, its image
// off by ~1e-8 relative at the square; the crossing of the two planes through x, (p x q) x k,
// lies on the plane exactly, and the interpolation only sets its length.
Vec3 cut_point(const Vec3& p, const Vec3& q, const Vec3& k) {
  const double sp = k.dot(p), sq = k.dot(q);
  const Vec3 rough = (sp * q - sq * p) / (sp - sq);
  Vec3 c = p.cross(q).cross(k);
  const double length = c.norm();
  if (!(length > 0)) return rough;
  c *= rough.norm() / length;
  return c.dot(rough) >= 0 ? c : Vec3(-c);
}

ImageBox padded_box(const std::vector<Vec2>& points, double radius) {
  ImageBox box;
  double size = 0;
  for (const Vec2& q : points) {
    box.extend(q);
    size = std::max(size, q.norm());
  }
  const double pad = radius * (1 + size);
  box.min().array() -= pad;
  box.max().array() += pad;
  return box;
}

// Measured in the image, the metric the cones and clusters use, and not by the edge's plane
// alone: a very short edge has a plane known only roughly, and its badly conditioned crossings
// land far beyond its ends while still "on" its plane; an angular end test lets them through,
// since near the horizon a relative image distance of 1e-10 is an angle far below double
// precision. Measured from the nearer end, so that a long edge reaching from near the zenith to
// the square keeps its precision at the near end.
double relative_segment_distance(const Vec2& a, const Vec2& b, const Vec2& q) {
  const Vec2 ab = b - a;
  const double length = ab.norm();
  if (!(length > 0)) return relative_distance(q, a);
  const Vec2 u = ab / length;
  const bool from_a = (q - a).dot(u) < 0.5 * length;
  const Vec2 r = q - (from_a ? a : b);
  const double along = r.dot(u);
  if (from_a ? along < 0 : along > 0) return r.norm() / (1 + q.norm());
  return (r - along * u).norm() / (1 + q.norm());
}

uint64_t pair_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

void add_faces_in_square(LocalPicture& picture, const LocalFrame& frame,
                         const std::vector<EmittingFace>& faces, double in_plane,
                         const std::vector<char>* emitting, const std::vector<int>* subset) {
  const size_t count = subset ? subset->size() : faces.size();
  for (size_t index = 0; index < count; ++index) {
    const size_t i = subset ? static_cast<size_t>((*subset)[index]) : index;
    const EmittingFace& face = faces[i];
    const double offset = plane_offset_from(frame.x, face.vertices.front(), face.normal);
    if (std::abs(offset) <= in_plane) continue;  // x in its plane: no solid angle
    std::vector<Vec3> loop;
    std::vector<char> flags(face.on_boundary.begin(), face.on_boundary.end());
    for (const Vec3& v : face.vertices) loop.push_back(frame.local(v));
    if (offset < 0) {
      // x in front: reverse so the interior is on the k . d >= 0 side of k_i = v_i x v_{i+1}.
      const size_t m = loop.size();
      std::reverse(loop.begin(), loop.end());
      std::vector<char> reversed(m);
      for (size_t j = 0; j < m; ++j) reversed[j] = flags[(2 * m - 2 - j) % m];
      flags = std::move(reversed);
    }
    for (size_t c = 0; c < 4 && loop.size() >= 3; ++c) {
      clip_to_plane(loop, flags, square_planes()[c], static_cast<char>(kCutBySquare + c));
    }
    // Drop repeated points (a clip exactly through a vertex): of p_j = p_j+1, p_j+1 goes with
    // the degenerate edge j, so edge j+1 keeps its flag; at the wrap, p_j itself goes.
    for (size_t j = 0; j < loop.size() && loop.size() >= 3;) {
      const size_t next = (j + 1) % loop.size();
      if ((loop[j] - loop[next]).norm() <= 1e-15 * loop[j].norm()) {
        loop.erase(loop.begin() + static_cast<long>(next == 0 ? j : next));
        flags.erase(flags.begin() + static_cast<long>(j));
      } else {
        ++j;
      }
    }
    if (loop.size() < 3) continue;
    LocalFace lf;
    lf.face = static_cast<int>(i);
    lf.normal = frame.rotate(face.normal);
    lf.offset = offset;
    // The receiver sees the front when it lies in front of the plane (offset < 0).
    const bool radiates = !emitting || (*emitting)[i];
    lf.exitance = offset < 0 && radiates ? face.exitance : Rgb::Zero();
    lf.transmittance = face.transmittance;
    const size_t m = loop.size();
    for (size_t j = 0; j < m; ++j) {
      lf.dirs.push_back(loop[j].normalized());
      lf.image.push_back(image_of(loop[j]));
      Vec3 k = loop[j].cross(loop[(j + 1) % m]);
      if (flags[j] >= kCutBySquare && k.norm() > 0) {
        // Along the square the plane is known exactly; from two cut points close together it
        // would not be (their crossings with other edges would land far off).
        const Vec3& exact = square_planes()[flags[j] - kCutBySquare];
        k = exact.dot(k) >= 0 ? exact : Vec3(-exact);
      }
      lf.k.push_back(k.norm() > 0 ? Vec3(k.normalized()) : Vec3::Zero());
    }
    lf.silhouette = std::move(flags);
    lf.box = padded_box(lf.image, kNape);
    if (lf.exitance != Rgb::Zero())
      picture.emitter_boxes.push_back(padded_box(lf.image, kCullMargin));
    picture.faces.push_back(std::move(lf));
  }
}

void add_features(LocalPicture& picture, const LocalFrame& frame,
                  const std::vector<EmittingFace>& faces, const std::vector<Segment>& segments,
                  const std::vector<char>* polygon_present, const EmitterCulling& culling) {
  for (LocalFace& f : picture.faces) {
    f.first_feature = static_cast<int>(picture.features.size());
    const size_t m = f.dirs.size();
    for (size_t j = 0; j < m; ++j) {
      picture.features.push_back({f.dirs[j], f.dirs[(j + 1) % m], f.k[j], f.image[j],
                                  f.image[(j + 1) % m], faces[f.face].polygon,
                                  f.silhouette[j] != 0});
      picture.feature_boxes.push_back(padded_box({f.image[j], f.image[(j + 1) % m]}, kNape));
    }
  }
  for (const Segment& s : segments) {
    if (polygon_present && !((*polygon_present)[s.polygon_a] && (*polygon_present)[s.polygon_b]))
      continue;
    Vec3 a = frame.local(s.a), b = frame.local(s.b);
    bool inside = true;
    for (const Vec3& plane : square_planes()) {
      const double sa = plane.dot(a), sb = plane.dot(b);
      if (sa < 0 && sb < 0) inside = false;
      if (!inside) break;
      if (sa < 0) a = cut_point(a, b, plane);
      if (sb < 0) b = cut_point(a, b, plane);
    }
    if (!inside) continue;
    const Vec3 k = a.cross(b);
    if (!(k.norm() > 0)) continue;
    const Vec3 da = a.normalized(), db = b.normalized();
    const ImageBox box = padded_box({image_of(a), image_of(b)}, kNape);
    if (!culling.near_emitter(box)) continue;
    picture.features.push_back({da, db, k.normalized(), image_of(a), image_of(b), -1, true});
    picture.feature_boxes.push_back(box);
    picture.candidates.push_back({da, image_of(a), true});
    picture.candidates.push_back({db, image_of(b), true});
  }
}

void add_vertices_and_crossings(LocalPicture& picture) {
  std::vector<Candidate>& candidates = picture.candidates;
  const std::vector<Feature>& features = picture.features;
  for (LocalFace& f : picture.faces) {
    f.first_vertex = static_cast<int>(picture.vertex_candidate.size());
    for (size_t j = 0; j < f.dirs.size(); ++j) {
      picture.vertex_candidate.push_back(static_cast<int>(candidates.size()));
      candidates.push_back({f.dirs[j], f.image[j], true});
    }
  }
  std::vector<int> silhouettes;
  std::vector<ImageBox> silhouette_boxes;
  for (size_t i = 0; i < features.size(); ++i) {
    if (features[i].silhouette && features[i].k != Vec3::Zero()) {
      silhouettes.push_back(static_cast<int>(i));
      silhouette_boxes.push_back(picture.feature_boxes[i]);
    }
  }
  const ImageBoxTree all_features(picture.feature_boxes);
  const ImageBoxTree silhouette_tree(silhouette_boxes);
  silhouette_tree.pairs(all_features, [&](int s_index, int other) {
    const int s = silhouettes[s_index];
    if (s == other || (features[other].silhouette && other < s)) return;  // each pair once
    const Feature& p = features[s];
    const Feature& q = features[other];
    if (q.k == Vec3::Zero() || (p.polygon >= 0 && p.polygon == q.polygon)) return;
    Vec3 where;
    if (!arcs_cross(p, q, &where)) return;
    picture.crossing.emplace(pair_key(s, other), static_cast<int>(candidates.size()));
    candidates.push_back({where, image_of(where), false});
  });
}

}  // namespace rad::vertex_detail
