#include "localpass/vertex_tracing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <unordered_map>

#include "localpass/angular_spans.h"
#include "localpass/image_box_tree.h"
#include "localpass/interpenetration.h"
#include "localpass/vertex_formula.h"
#include "scene/error.h"
#include "scene/polygon.h"

namespace rad {
namespace {

constexpr double kNape = VertexTracer::kNapeAngle;
/// Emitter culling keeps everything within this relative distance of an emitter's box: more
/// than any cone radius used (the nape angle plus the spread of merged candidates).
constexpr double kCullMargin = 1e-6;

Vec2 image_of(const Vec3& d) { return {d.x() / d.z(), d.y() / d.z()}; }

/// Distance between image points relative to 1 + |q|: about the angle between the directions
/// near the zenith, and the same relative precision next to the horizon.
double relative_distance(const Vec2& a, const Vec2& b) {
  return (a - b).norm() / (1 + std::min(a.norm(), b.norm()));
}

/// The box of image points, padded by `radius` relative to their size.
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

/// A face as seen from x: local coordinates (x at the origin, receiver normal +z), clipped at
/// the image square, as a loop whose interior is on the k . d >= 0 side of every edge plane.
struct LocalFace {
  int face = -1;
  Vec3 normal;
  double offset = 0;
  Rgb exitance = Rgb::Zero();
  std::vector<Vec3> dirs;        ///< Unit vertex directions...
  std::vector<Vec2> image;       ///< ...and their images q = (d_x, d_y) / d_z.
  std::vector<Vec3> k;           ///< Edge i (dirs i -> i+1): unit normal of its plane through x (0: degenerate).
  std::vector<char> silhouette;  ///< Edge flag: 0 inside the polygon, else a silhouette (see kCutBySquare).
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
  bool silhouette = false;
};

struct Candidate {
  Vec3 d;
  Vec2 q;
  bool intrinsic;  ///< A vertex (polygon vertex, cut by the square, or intersection end)
};

/// Half side of the square the image is clipped to (001 §3.1: "clip against a large bounding
/// square on the image plane"). What lies outside has a projected solid angle below
/// pi / (1 + L^2), an irradiance error below 1e-16 of the largest exitance. Clipping at a small
/// height above the tangent plane instead cuts every face along its own line (a near face at
/// 1/100 of the height's image distance of a far one), so far faces show through a band under
/// near ones that reach the tangent plane; the band's vertex terms are O(1) each, and they fail
/// to cancel. The square's four planes pass through x and are shared by every face: a face
/// that hides another up to the horizon hides it up to the square.
constexpr double kImageBound = 1e8;

/// The square's planes through x: k . p >= 0 keeps |u| <= L z, |v| <= L z (and so z > 0).
const std::array<Vec3, 4>& square_planes() {
  static const std::array<Vec3, 4> planes = {Vec3(-1, 0, kImageBound), Vec3(1, 0, kImageBound),
                                             Vec3(0, -1, kImageBound), Vec3(0, 1, kImageBound)};
  return planes;
}

/// Edge flags: 0 inside the polygon, 1 on its boundary, kCutBySquare + i along square plane i
/// (nonzero: a silhouette, the face ends there).
constexpr char kCutBySquare = 2;

/// Where segment p -> q crosses the plane k . d = 0 through x (k . p and k . q of opposite
/// signs). Interpolating would give the point's height as a difference of two large numbers,
/// its image off by ~1e-8 relative at the square; the crossing of the two planes through x,
/// (p x q) x k, lies on the plane exactly, and the interpolation only sets its length.
Vec3 cut_point(const Vec3& p, const Vec3& q, const Vec3& k) {
  const double sp = k.dot(p), sq = k.dot(q);
  const Vec3 rough = (sp * q - sq * p) / (sp - sq);
  Vec3 c = p.cross(q).cross(k);
  const double length = c.norm();
  if (!(length > 0)) return rough;
  c *= rough.norm() / length;
  return c.dot(rough) >= 0 ? c : Vec3(-c);
}

/// Clips a convex loop with per-edge flags to k . p >= 0 (Sutherland-Hodgman); the new edge
/// along the cut gets `cut_flag`.
void clip_to_plane(std::vector<Vec3>& loop, std::vector<char>& flags, const Vec3& k, char cut_flag) {
  std::vector<Vec3> out;
  std::vector<char> out_flags;
  const size_t n = loop.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec3& p = loop[i];
    const Vec3& q = loop[(i + 1) % n];
    const double sp = k.dot(p), sq = k.dot(q);
    const bool p_in = sp >= 0, q_in = sq >= 0;
    const auto cut = [&] { return cut_point(p, q, k); };
    if (p_in) {
      out.push_back(p);
      out_flags.push_back(flags[i]);
      if (!q_in) {
        out.push_back(cut());
        out_flags.push_back(cut_flag);
      }
    } else if (q_in) {
      out.push_back(cut());
      out_flags.push_back(flags[i]);
    }
  }
  loop = std::move(out);
  flags = std::move(out_flags);
}

/// Distance from image point q to the image segment a -> b, relative to 1 + |q| (as
/// relative_distance). Measured in the image, the metric the cones and clusters use, and not by
/// the edge's plane alone: a very short edge has a plane known only roughly, and its badly
/// conditioned crossings land far beyond its ends while still "on" its plane; an angular end
/// test lets them through, since near the horizon a relative image distance of 1e-10 is an
/// angle far below double precision. Measured from the nearer end, so that a long edge reaching
/// from near the zenith to the square keeps its precision at the near end.
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
  if (!(relative_segment_distance(p.qa, p.qb, image) < kNape && relative_segment_distance(q.qa, q.qb, image) < kNape)) {
    return false;
  }
  *where = c;
  return true;
}

/// Union-find over candidates.
struct Clusters {
  std::vector<int> parent;
  explicit Clusters(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  bool unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    parent[std::max(a, b)] = std::min(a, b);
    return true;
  }
};

uint64_t pair_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

/// What one face shows in the cone of radius `radius` around d (001 Algorithm 1's three cases,
/// Fig. 5), plus the features and vertices it brought (for the bookkeeping of §5).
void classify(const LocalFace& f, const Vec3& d, const Vec2& q, double radius, std::vector<SpanEntry>& entries,
              std::vector<int>& features, std::vector<int>& vertices) {
  const int n = static_cast<int>(f.dirs.size());
  const auto next = [n](int i) { return (i + 1) % n; };
  const auto prev = [n](int i) { return (i + n - 1) % n; };
  SpanEntry entry;
  entry.normal = f.normal;
  entry.offset = f.offset;
  entry.order = f.face;
  entry.exitance = f.exitance;

  int nearest = -1;
  double nearest_distance = radius;
  int near_count = 0;
  for (int i = 0; i < n; ++i) {
    const double distance = relative_distance(f.image[i], q);
    if (distance < radius) {
      ++near_count;
      if (distance < nearest_distance) {
        nearest_distance = distance;
        nearest = i;
      }
    }
  }
  if (near_count == n) return;  // smaller than the cone: subtends < pi radius^2
  if (nearest >= 0) {
    // A vertex span. Consecutive vertices inside the cone collapse into one (a very short edge
    // seen from afar): the span runs from the edge leaving the run to the edge entering it.
    int first = nearest, last = nearest;
    while (relative_distance(f.image[prev(first)], q) < radius) first = prev(first);
    while (relative_distance(f.image[next(last)], q) < radius) last = next(last);
    const Vec3& k_out = f.k[last];
    const Vec3& k_in = f.k[prev(first)];
    if (k_out == Vec3::Zero() || k_in == Vec3::Zero()) return;
    entry.kind = SpanEntry::Kind::vertex;
    entry.start = k_out;
    entry.end = k_in;
    entries.push_back(entry);
    for (int i = prev(first);; i = next(i)) {
      features.push_back(f.first_feature + i);
      if (i == last) break;
    }
    for (int i = first;; i = next(i)) {
      vertices.push_back(f.first_vertex + i);
      if (i == last) break;
    }
    return;
  }
  int best = -1;
  double best_distance = radius;
  bool inside = true;
  for (int i = 0; i < n; ++i) {
    if (f.k[i] == Vec3::Zero()) continue;
    if (f.k[i].dot(d) <= 0) inside = false;
    const double distance = relative_line_distance(f.k[i], q);
    if (distance < best_distance && relative_segment_distance(f.image[i], f.image[next(i)], q) < radius) {
      best_distance = distance;
      best = i;
    }
  }
  if (best >= 0) {
    entry.kind = SpanEntry::Kind::edge;
    entry.start = f.k[best];
    entries.push_back(entry);
    features.push_back(f.first_feature + best);
    return;
  }
  if (inside) {
    entry.kind = SpanEntry::Kind::full;
    entries.push_back(entry);
  }
}

}  // namespace

VertexTracer::VertexTracer(const Scene& scene) : VertexTracer(scene, faces_from_polygons(scene)) {}

VertexTracer::VertexTracer(const Scene& scene, std::vector<EmittingFace> faces)
    : scene_(scene), faces_(std::move(faces)) {
  for (const EmittingFace& f : faces_) {
    if (f.polygon < 0 || f.polygon >= static_cast<int>(scene.polygons.size()) || f.vertices.size() < 3 ||
        f.on_boundary.size() != f.vertices.size()) {
      throw Error("vertex tracing: a face refers to polygon " + std::to_string(f.polygon) + " or has " +
                  std::to_string(f.vertices.size()) + " vertices and " + std::to_string(f.on_boundary.size()) +
                  " edge flags");
    }
  }
  for (const Interpenetration& s : interpenetration_segments(scene)) {
    intersections_.push_back({s.a, s.b, s.polygon_a, s.polygon_b});
  }
  const double diagonal = scene.bounds().diagonal();
  in_plane_ = 1e-12 * diagonal;
}

VertexTraceResult VertexTracer::gather(const Vec3& x, const Vec3& n, const Options& options) const {
  if (options.emitting && options.emitting->size() != faces_.size()) {
    throw Error("vertex tracing: " + std::to_string(options.emitting->size()) + " emitting flags for " +
                std::to_string(faces_.size()) + " faces");
  }
  VertexTraceResult result;
  const PlaneFrame frame(Vec3::Zero(), n);
  const auto rotate = [&](const Vec3& r) { return Vec3(frame.u.dot(r), frame.v.dot(r), n.dot(r)); };
  const auto local = [&](const Vec3& p) { return rotate(p - x); };

  // 1. The faces inside the image square (above the horizon), in local coordinates.
  std::vector<LocalFace> faces;
  std::vector<ImageBox> emitter_boxes;
  std::vector<char> polygon_present;  // with a face subset: polygons that have a face in it
  if (options.faces) {
    polygon_present.assign(scene_.polygons.size(), 0);
    for (const int i : *options.faces) polygon_present[faces_[i].polygon] = 1;
  }
  const size_t face_count = options.faces ? options.faces->size() : faces_.size();
  for (size_t index = 0; index < face_count; ++index) {
    const size_t i = options.faces ? static_cast<size_t>((*options.faces)[index]) : index;
    const EmittingFace& face = faces_[i];
    const Polygon& polygon = scene_.polygons[face.polygon];
    const double offset = polygon.normal.dot(face.vertices.front() - x);
    if (std::abs(offset) <= in_plane_) continue;  // x in its plane: no solid angle
    std::vector<Vec3> loop;
    std::vector<char> flags(face.on_boundary.begin(), face.on_boundary.end());
    for (const Vec3& v : face.vertices) loop.push_back(local(v));
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
    lf.normal = rotate(polygon.normal);
    lf.offset = offset;
    // The receiver sees the front when it lies in front of the plane (offset < 0).
    const bool radiates = !options.emitting || (*options.emitting)[i];
    lf.exitance = offset < 0 && radiates ? face.exitance : Rgb::Zero();
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
    if (lf.exitance != Rgb::Zero()) emitter_boxes.push_back(padded_box(lf.image, kCullMargin));
    faces.push_back(std::move(lf));
  }
  if (emitter_boxes.empty()) return result;
  // Only what may show in front of an emitter's image box matters (001 §4.1), box by box: the
  // emitters of a local-pass batch lie in many directions, and one box around them all would
  // keep nearly everything.
  const ImageBoxTree emitter_tree(emitter_boxes);
  const auto near_emitter = [&](const ImageBox& box) { return !options.cull_to_emitters || emitter_tree.any(box); };
  std::erase_if(faces, [&](const LocalFace& f) { return !near_emitter(f.box); });

  // 2. Features: face edges, then intersection segments inside the square.
  std::vector<Feature> features;
  std::vector<ImageBox> feature_boxes;
  for (LocalFace& f : faces) {
    f.first_feature = static_cast<int>(features.size());
    const size_t m = f.dirs.size();
    for (size_t j = 0; j < m; ++j) {
      features.push_back({f.dirs[j], f.dirs[(j + 1) % m], f.k[j], f.image[j], f.image[(j + 1) % m],
                          faces_[f.face].polygon, f.silhouette[j] != 0});
      feature_boxes.push_back(padded_box({f.image[j], f.image[(j + 1) % m]}, kNape));
    }
  }
  std::vector<Candidate> candidates;
  for (const Segment& s : intersections_) {
    if (options.faces && !(polygon_present[s.polygon_a] && polygon_present[s.polygon_b])) continue;
    Vec3 a = local(s.a), b = local(s.b);
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
    if (!near_emitter(box)) continue;
    features.push_back({da, db, k.normalized(), image_of(a), image_of(b), -1, true});
    feature_boxes.push_back(box);
    candidates.push_back({da, image_of(a), true});
    candidates.push_back({db, image_of(b), true});
  }

  // 3. Candidates: every vertex, and every apparent crossing of a silhouette with any feature
  // of another polygon (two edges inside polygons cannot both be seen; 001 §4.2).
  std::vector<int> vertex_candidate;
  for (LocalFace& f : faces) {
    f.first_vertex = static_cast<int>(vertex_candidate.size());
    for (size_t j = 0; j < f.dirs.size(); ++j) {
      vertex_candidate.push_back(static_cast<int>(candidates.size()));
      candidates.push_back({f.dirs[j], f.image[j], true});
    }
  }
  std::vector<int> silhouettes;
  std::vector<ImageBox> silhouette_boxes;
  for (size_t i = 0; i < features.size(); ++i) {
    if (features[i].silhouette && features[i].k != Vec3::Zero()) {
      silhouettes.push_back(static_cast<int>(i));
      silhouette_boxes.push_back(feature_boxes[i]);
    }
  }
  const ImageBoxTree all_features(feature_boxes);
  const ImageBoxTree silhouette_tree(silhouette_boxes);
  std::unordered_map<uint64_t, int> crossing;
  silhouette_tree.pairs(all_features, [&](int s_index, int other) {
    const int s = silhouettes[s_index];
    if (s == other || (features[other].silhouette && other < s)) return;  // each pair once
    const Feature& p = features[s];
    const Feature& q = features[other];
    if (q.k == Vec3::Zero() || (p.polygon >= 0 && p.polygon == q.polygon)) return;
    Vec3 where;
    if (!arcs_cross(p, q, &where)) return;
    crossing.emplace(pair_key(s, other), static_cast<int>(candidates.size()));
    candidates.push_back({where, image_of(where), false});
  });
  result.candidates = static_cast<int>(candidates.size());

  // 4. Candidates closer than the nape angle (relative image distance) are one conjunctive
  // vertex. Sorted by log(1 + |q|), which two such candidates differ in by less than the angle.
  Clusters clusters(candidates.size());
  {
    std::vector<std::pair<double, int>> order;
    order.reserve(candidates.size());
    for (size_t i = 0; i < candidates.size(); ++i) order.emplace_back(std::log1p(candidates[i].q.norm()), static_cast<int>(i));
    std::sort(order.begin(), order.end());
    for (size_t i = 0; i < order.size(); ++i) {
      for (size_t j = i + 1; j < order.size() && order[j].first - order[i].first < kNape; ++j) {
        const int a = order[i].second, b = order[j].second;
        if (relative_distance(candidates[a].q, candidates[b].q) < kNape) clusters.unite(a, b);
      }
    }
  }

  // 5. Trace one cone per cluster. If a cone meets a vertex or a pair of edges whose own
  // candidate went to another cluster (an "unexpected incidence"), the two clusters are one
  // conjunctive vertex: merge and trace again, so nothing is counted twice (001 §3.4, §5).
  std::vector<ImageBox> face_boxes;
  for (const LocalFace& f : faces) face_boxes.push_back(f.box);
  const ImageBoxTree face_tree(face_boxes);
  struct Traced {
    Vec3 d;
    double radius;
    std::vector<SpanEntry> entries;
  };
  std::vector<Traced> traced;
  std::vector<SpanEntry> entries;
  std::vector<int> incident_features, incident_vertices;
  for (int round = 0;; ++round) {
    traced.clear();
    std::vector<std::vector<int>> groups;
    {
      std::unordered_map<int, int> group_of;
      for (size_t i = 0; i < candidates.size(); ++i) {
        const int root = clusters.find(static_cast<int>(i));
        const auto [it, added] = group_of.emplace(root, static_cast<int>(groups.size()));
        if (added) groups.emplace_back();
        groups[it->second].push_back(static_cast<int>(i));
      }
    }
    bool merged = false;
    for (const std::vector<int>& group : groups) {
      int representative = group.front();
      for (const int c : group) {
        if (candidates[c].intrinsic) {
          representative = c;
          break;
        }
      }
      const Vec3 d = candidates[representative].d;
      const Vec2 q = candidates[representative].q;
      if (!near_emitter(ImageBox(q, q))) continue;  // culled: no emitter can show here
      double spread = 0;
      for (const int c : group) spread = std::max(spread, relative_distance(candidates[c].q, q));
      const double radius = kNape + spread;
      entries.clear();
      incident_features.clear();
      incident_vertices.clear();
      const double reach = radius * (1 + q.norm());
      face_tree.query(ImageBox(q - Vec2::Constant(reach), q + Vec2::Constant(reach)), [&](int f) {
        classify(faces[f], d, q, radius, entries, incident_features, incident_vertices);
      });
      const int root = clusters.find(group.front());
      if (round < 8) {
        // Only candidates near the cone count: two nearly parallel features can both pass
        // through it and still cross far away, which is a different vertex.
        const auto merge = [&](int candidate) {
          if (relative_distance(candidates[candidate].q, q) < 4 * radius && clusters.unite(root, candidate)) {
            merged = true;
            ++result.slow_path;
          }
        };
        for (const int v : incident_vertices) merge(vertex_candidate[v]);
        for (size_t a = 0; a < incident_features.size(); ++a) {
          for (size_t b = a + 1; b < incident_features.size(); ++b) {
            const auto it = crossing.find(pair_key(incident_features[a], incident_features[b]));
            if (it != crossing.end()) merge(it->second);
          }
        }
      }
      if (group.size() > 1) ++result.conjunctive;
      traced.push_back({d, radius, entries});
    }
    if (!merged) break;
    result.conjunctive = 0;
  }

  // 6. Sum the contributions (001 eq. 9).
  Rgb sum = Rgb::Zero();
  for (const Traced& t : traced) {
    bool emits = false;
    for (const SpanEntry& e : t.entries) emits = emits || e.exitance != Rgb::Zero();
    if (emits) sum += angular_span_sum(t.d, t.entries, t.radius);
  }
  result.traced = static_cast<int>(traced.size());
  result.irradiance = sum / std::numbers::pi;
  return result;
}

}  // namespace rad
