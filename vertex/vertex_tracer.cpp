#include "vertex/vertex_tracer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <unordered_map>

#include "scene/error.h"
#include "scene/polygon.h"
#include "scene/polygon_faces.h"
#include "vertex/angular_spans.h"
#include "vertex/interpenetration.h"
#include "vertex/local_picture.h"

namespace rad {
namespace {

using namespace vertex_detail;

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

/// What one face shows in the cone of radius `radius` around d (001 Algorithm 1's three cases,
/// Fig. 5), plus the features and vertices it brought (for the bookkeeping of §5).
void classify(const LocalFace& f, const Vec3& d, const Vec2& q, double radius,
              std::vector<SpanEntry>& entries, std::vector<int>& features,
              std::vector<int>& vertices) {
  const int n = static_cast<int>(f.dirs.size());
  const auto next = [n](int i) { return (i + 1) % n; };
  const auto prev = [n](int i) { return (i + n - 1) % n; };
  SpanEntry entry;
  entry.normal = f.normal;
  entry.offset = f.offset;
  entry.order = f.face;
  entry.exitance = f.exitance;
  entry.transmittance = f.transmittance;

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
    if (distance < best_distance &&
        relative_segment_distance(f.image[i], f.image[next(i)], q) < radius) {
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

/// Step 4: candidates closer than the nape angle (relative image distance) are one conjunctive
/// vertex. Sorted by log(1 + |q|), which two such candidates differ in by less than the angle.
Clusters cluster_candidates(const std::vector<Candidate>& candidates) {
  Clusters clusters(candidates.size());
  std::vector<std::pair<double, int>> order;
  order.reserve(candidates.size());
  for (size_t i = 0; i < candidates.size(); ++i)
    order.emplace_back(std::log1p(candidates[i].q.norm()), static_cast<int>(i));
  std::sort(order.begin(), order.end());
  for (size_t i = 0; i < order.size(); ++i) {
    for (size_t j = i + 1; j < order.size() && order[j].first - order[i].first < kNape; ++j) {
      const int a = order[i].second, b = order[j].second;
      if (relative_distance(candidates[a].q, candidates[b].q) < kNape) clusters.unite(a, b);
    }
  }
  return clusters;
}

/// One traced cone: its axis, its radius and the spans it met.
struct TracedCone {
  Vec3 d;
  double radius;
  std::vector<SpanEntry> entries;
};

/// Step 5: one cone per cluster. If a cone meets a vertex or a pair of edges whose own
/// candidate went to another cluster (an "unexpected incidence"), the two clusters are one
/// conjunctive vertex: merge and trace again, so nothing is counted twice (001 §3.4, §5).
std::vector<TracedCone> trace_cones(const LocalPicture& picture, Clusters& clusters,
                                    const EmitterCulling& culling, VertexTraceResult& result) {
  const std::vector<Candidate>& candidates = picture.candidates;
  std::vector<ImageBox> face_boxes;
  for (const LocalFace& f : picture.faces) face_boxes.push_back(f.box);
  const ImageBoxTree face_tree(face_boxes);
  std::vector<TracedCone> traced;
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
      if (!culling.near_emitter(ImageBox(q, q))) continue;  // culled: no emitter can show here
      double spread = 0;
      for (const int c : group) spread = std::max(spread, relative_distance(candidates[c].q, q));
      const double radius = kNape + spread;
      entries.clear();
      incident_features.clear();
      incident_vertices.clear();
      const double reach = radius * (1 + q.norm());
      face_tree.query(ImageBox(q - Vec2::Constant(reach), q + Vec2::Constant(reach)), [&](int f) {
        classify(picture.faces[f], d, q, radius, entries, incident_features, incident_vertices);
      });
      const int root = clusters.find(group.front());
      if (round < 8) {
        // Only candidates near the cone count: two nearly parallel features can both pass
        // through it and still cross far away, which is a different vertex.
        const auto merge = [&](int candidate) {
          if (relative_distance(candidates[candidate].q, q) < 4 * radius &&
              clusters.unite(root, candidate)) {
            merged = true;
            ++result.slow_path;
          }
        };
        for (const int v : incident_vertices) merge(picture.vertex_candidate[v]);
        for (size_t a = 0; a < incident_features.size(); ++a) {
          for (size_t b = a + 1; b < incident_features.size(); ++b) {
            const auto it =
                picture.crossing.find(pair_key(incident_features[a], incident_features[b]));
            if (it != picture.crossing.end()) merge(it->second);
          }
        }
      }
      if (group.size() > 1) ++result.conjunctive;
      traced.push_back({d, radius, entries});
    }
    if (!merged) break;
    result.conjunctive = 0;
  }
  return traced;
}

/// Step 6: the sum of the vertices' contributions (001 eq. 9), as irradiance.
Rgb sum_contributions(const std::vector<TracedCone>& traced) {
  Rgb sum = Rgb::Zero();
  for (const TracedCone& t : traced) {
    bool emits = false;
    for (const SpanEntry& e : t.entries) emits = emits || e.exitance != Rgb::Zero();
    if (emits) sum += angular_span_sum(t.d, t.entries, t.radius);
  }
  return sum / std::numbers::pi;
}

}  // namespace

/// ExactGatherSession of vertex tracing: a fresh trace per step, summed.
class VertexTracer::Session final : public ExactGatherSession {
 public:
  Session(const VertexTracer& tracer, const Vec3& x, const Vec3& n)
      : tracer_(tracer), x_(x), n_(n), radiating_(tracer.faces_.size(), 0) {}

  ExactGatherTotal step(const std::vector<int>& radiating,
                        const std::vector<int>& occluders) override {
    std::vector<int> faces = radiating;
    faces.insert(faces.end(), occluders.begin(), occluders.end());
    std::ranges::sort(faces);
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    for (const int f : radiating) radiating_[f] = 1;
    Options options;
    options.emitting = &radiating_;
    options.faces = &faces;
    total_ += tracer_.gather(x_, n_, options).irradiance;
    for (const int f : radiating) radiating_[f] = 0;
    projected_ += static_cast<int>(faces.size());
    return {total_, std::nullopt};
  }
  int projected() const override { return projected_; }

 private:
  const VertexTracer& tracer_;
  Vec3 x_, n_;
  std::vector<char> radiating_;
  Rgb total_ = Rgb::Zero();
  int projected_ = 0;
};

VertexTracer::VertexTracer(const Scene& scene) : VertexTracer(scene, faces_from_polygons(scene)) {}

VertexTracer::VertexTracer(const Scene& scene, std::vector<EmittingFace> faces)
    : polygon_count_(scene.polygons.size()),
      faces_(std::move(faces)),
      in_plane_(scene.tolerance().in_plane) {
  for (const EmittingFace& f : faces_) {
    if (f.polygon < 0 || f.polygon >= static_cast<int>(scene.polygons.size()) ||
        f.vertices.size() < 3 || f.on_boundary.size() != f.vertices.size()) {
      throw Error("vertex tracing: a face refers to polygon " + std::to_string(f.polygon) +
                  " or has " + std::to_string(f.vertices.size()) + " vertices and " +
                  std::to_string(f.on_boundary.size()) + " edge flags");
    }
  }
  for (const Interpenetration& s : interpenetration_segments(scene)) {
    intersections_.push_back({s.a, s.b, s.polygon_a, s.polygon_b});
  }
}

VertexTracer::~VertexTracer() = default;

std::unique_ptr<ExactGatherSession> VertexTracer::start(const Vec3& x, const Vec3& n) const {
  return std::make_unique<Session>(*this, x, n);
}

VertexTraceResult VertexTracer::gather(const Vec3& x, const Vec3& n, const Options& options) const {
  if (options.emitting && options.emitting->size() != faces_.size()) {
    throw Error("vertex tracing: " + std::to_string(options.emitting->size()) +
                " emitting flags for " + std::to_string(faces_.size()) + " faces");
  }
  VertexTraceResult result;
  const PlaneFrame plane(Vec3::Zero(), n);
  const LocalFrame frame{x, plane.u, plane.v, n};
  std::vector<char> polygon_present;  // with a face subset: polygons that have a face in it
  if (options.faces) {
    polygon_present.assign(polygon_count_, 0);
    for (const int i : *options.faces) polygon_present[faces_[i].polygon] = 1;
  }

  LocalPicture picture;
  add_faces_in_square(picture, frame, faces_, in_plane_, options.emitting, options.faces);
  if (picture.emitter_boxes.empty()) return result;
  const ImageBoxTree emitter_tree(picture.emitter_boxes);
  const EmitterCulling culling{&emitter_tree, options.cull_to_emitters};
  std::erase_if(picture.faces, [&](const LocalFace& f) { return !culling.near_emitter(f.box); });
  add_features(picture, frame, faces_, intersections_, options.faces ? &polygon_present : nullptr,
               culling);
  add_vertices_and_crossings(picture);
  result.candidates = static_cast<int>(picture.candidates.size());

  Clusters clusters = cluster_candidates(picture.candidates);
  const std::vector<TracedCone> traced = trace_cones(picture, clusters, culling, result);
  result.traced = static_cast<int>(traced.size());
  result.irradiance = sum_contributions(traced);
  return result;
}

}  // namespace rad
