#include "specular/glossy_transfer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "scene/polygon.h"
#include "scene/ray_caster.h"

namespace rad {
namespace {

/// A point source: isotropic (a point light), or one piece of an emitter, Lambertian about
/// `normal` (intensity (M / pi) area cos toward a direction).
struct Source {
  Vec3 position;
  Rgb intensity;  ///< Isotropic: I; Lambertian: (M / pi) area
  Vec3 normal = Vec3::Zero();
  bool lambertian = false;
};

/// A polygon's triangles with their vertex normals (the polygon's normal when not smooth).
std::vector<GlossyTriangle> triangles_of(const Polygon& p) {
  std::vector<GlossyTriangle> out;
  for (const auto& [a, b, c] : triangulate(project_to_plane(p.vertices, p.normal))) {
    GlossyTriangle t;
    t.vertex = {p.vertices[a], p.vertices[b], p.vertices[c]};
    if (p.vertex_normals.empty()) {
      t.normal = {p.normal, p.normal, p.normal};
    } else {
      t.normal = {p.vertex_normals[a], p.vertex_normals[b], p.vertex_normals[c]};
    }
    out.push_back(t);
  }
  return out;
}

/// t split into n^2 similar triangles (midpoint grid), normals interpolated.
std::vector<GlossyTriangle> split(const GlossyTriangle& t, int n) {
  const auto at = [&](int i, int j) {
    const double a = static_cast<double>(i) / n, b = static_cast<double>(j) / n;
    return std::pair<Vec3, Vec3>{
        (1 - a - b) * t.vertex[0] + a * t.vertex[1] + b * t.vertex[2],
        ((1 - a - b) * t.normal[0] + a * t.normal[1] + b * t.normal[2]).normalized()};
  };
  std::vector<GlossyTriangle> out;
  const auto add = [&](const std::pair<Vec3, Vec3>& p, const std::pair<Vec3, Vec3>& q,
                       const std::pair<Vec3, Vec3>& r) {
    out.push_back({{p.first, q.first, r.first}, {p.second, q.second, r.second}, t.transmits});
  };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; i + j < n; ++j) {
      add(at(i, j), at(i + 1, j), at(i, j + 1));
      if (i + j + 1 < n) add(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return out;
}

}  // namespace

GlossyTransfer::~GlossyTransfer() = default;

GlossyTransfer::GlossyTransfer(const Scene& scene, const GlossySettings& settings)
    : hierarchy_(settings.hierarchy) {
  bool glossy = false;
  for (const Material& m : scene.materials) glossy = glossy || m.is_glossy();
  if (!glossy) return;
  // The sources.
  std::vector<Source> sources;
  for (const PointLight& light : scene.lights) sources.push_back({light.position, light.intensity});
  const int light_split = std::max(1, settings.light_split);
  for (const Polygon& p : scene.polygons) {
    const Material& m = scene.materials[p.material];
    if (!m.is_emitter()) continue;
    for (const GlossyTriangle& t : triangles_of(p)) {
      for (const GlossyTriangle& piece : split(t, light_split)) {
        const auto& v = piece.vertex;
        const double area = 0.5 * (v[1] - v[0]).cross(v[2] - v[0]).norm();
        sources.push_back(
            {(v[0] + v[1] + v[2]) / 3, m.emission * (area / std::numbers::pi), p.normal, true});
      }
    }
  }
  // The beams: every source through every scatterer piece it sees.
  const RayCaster caster(scene);
  const double offset = scene.tolerance().ray_offset;
  const int pieces = std::max(1, settings.split);
  for (size_t i = 0; i < scene.polygons.size(); ++i) {
    const Polygon& p = scene.polygons[i];
    const Material& m = scene.materials[p.material];
    if (!m.is_glossy()) continue;
    // A glossy mirror reflects its specular part from its front; a roughened pane passes its
    // glossy transmittance from either side (003 Fig. 13).
    std::vector<std::pair<bool, Rgb>> kinds;
    if (m.is_glossy_mirror()) kinds.push_back({false, m.specular});
    if (m.is_glossy_pane()) kinds.push_back({true, m.glossy_transmittance});
    for (const auto& [transmits, weight] : kinds) {
      for (GlossyTriangle t : triangles_of(p)) {
        t.transmits = transmits;
        for (const GlossyTriangle& piece : split(t, pieces)) {
          const Vec3 centre = (piece.vertex[0] + piece.vertex[1] + piece.vertex[2]) / 3;
          const int piece_index = static_cast<int>(piece_centre_.size());
          piece_centre_.push_back(centre);
          piece_normal_.push_back(p.normal);
          for (const Source& s : sources) {
            const Vec3 to = centre - s.position;
            const double distance = to.norm();
            if (!(distance > 2 * offset)) continue;
            const Vec3 w = to / distance;
            Rgb intensity = s.intensity;
            if (s.lambertian) intensity *= std::max(0.0, s.normal.dot(w));
            if (intensity == Rgb::Zero()) continue;
            if (!transmits && !(p.normal.dot(-w) > 0)) continue;  // a mirror's back
            // First-order visibility: the source sees the piece's centre (through filters).
            const Vec3 origin = s.lambertian ? Vec3(s.position + offset * s.normal) : s.position;
            const Vec3 leg = centre - origin;
            const double length = leg.norm();
            const Rgb passed =
                caster.transmittance({origin, leg / length}, offset, length - offset, offset);
            if (passed == Rgb::Zero()) continue;
            GlossyBeam beam(s.position, intensity.cwiseProduct(passed), piece, weight, m.gloss);
            if (beam.empty()) continue;
            beams_.push_back(std::move(beam));
            beam_piece_.push_back(piece_index);
          }
        }
      }
    }
  }
  // Each beam's sphere and cone, widened by cutoff sigma.
  const double cutoff = settings.cutoff;
  for (const GlossyBeam& beam : beams_) {
    const auto& v = beam.triangle().vertex;
    Node bound;
    bound.centre = (v[0] + v[1] + v[2]) / 3;
    for (const Vec3& corner : v)
      bound.radius = std::max(bound.radius, (corner - bound.centre).norm());
    bound.axis = beam.mean_direction();
    // The scattered directions at the corners, the edges' midpoints and the centre (smooth
    // normals interpolate between the corners' directions).
    double spread = 0;
    const std::array<std::array<double, 3>, 7> at{{{1, 0, 0},
                                                   {0, 1, 0},
                                                   {0, 0, 1},
                                                   {0.5, 0.5, 0},
                                                   {0, 0.5, 0.5},
                                                   {0.5, 0, 0.5},
                                                   {1.0 / 3, 1.0 / 3, 1.0 / 3}}};
    for (const auto& w : at) {
      const Vec3 point = w[0] * v[0] + w[1] * v[1] + w[2] * v[2];
      spread = std::max(spread, angle_between(bound.axis, beam.scattered(point, w)));
    }
    bound.half_angle = std::min(std::numbers::pi, spread + cutoff * beam.sigma());
    leaf_bounds_.push_back(bound);
  }
  if (settings.shadows && !beams_.empty()) {
    caster_ = std::make_unique<RayCaster>(scene);
    offset_ = offset;
  }
  order_.resize(beams_.size());
  for (size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<int>(i);
  if (!beams_.empty()) build(0, static_cast<int>(beams_.size()));
}

int GlossyTransfer::build(int first, int count) {
  Node node;
  node.first = first, node.count = count;
  Vec3 centre = Vec3::Zero(), axis = Vec3::Zero();
  for (int k = first; k < first + count; ++k) {
    centre += leaf_bounds_[order_[k]].centre;
    axis += leaf_bounds_[order_[k]].axis;
  }
  node.centre = centre / count;
  node.axis = axis.norm() > 0 ? Vec3(axis.normalized()) : Vec3::UnitZ();
  node.half_angle = axis.norm() > 0 ? 0.0 : std::numbers::pi;
  for (int k = first; k < first + count; ++k) {
    const Node& b = leaf_bounds_[order_[k]];
    node.radius = std::max(node.radius, (b.centre - node.centre).norm() + b.radius);
    node.half_angle =
        std::min(std::numbers::pi,
                 std::max(node.half_angle, angle_between(node.axis, b.axis) + b.half_angle));
  }
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back(node);
  if (count <= 4) return index;
  // Split at the median along the longest side of the centres' box.
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (int k = first; k < first + count; ++k) {
    lo = lo.cwiseMin(leaf_bounds_[order_[k]].centre);
    hi = hi.cwiseMax(leaf_bounds_[order_[k]].centre);
  }
  int axis_index = 0;
  (hi - lo).maxCoeff(&axis_index);
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half,
                   order_.begin() + first + count, [&](int a, int b) {
                     const double ca = leaf_bounds_[a].centre[axis_index];
                     const double cb = leaf_bounds_[b].centre[axis_index];
                     return ca != cb ? ca < cb : a < b;
                   });
  const int left = build(first, half);
  const int right = build(first + half, count - half);
  nodes_[index].left = left, nodes_[index].right = right;
  return index;
}

bool GlossyTransfer::may_reach(const Node& node, const Vec3& x) const {
  if (node.half_angle >= std::numbers::pi) return true;
  const Vec3 v = x - node.centre;
  const double d = v.norm();
  if (d <= node.radius) return true;
  return angle_between(v, node.axis) <= node.half_angle + std::asin(node.radius / d);
}

GlossyTransfer::Result GlossyTransfer::irradiance(const Vec3& x, const Vec3& n) const {
  Result result;
  if (beams_.empty()) return result;
  // Second-order shadows: what passes between x and each piece's centre, asked once per piece.
  std::vector<Rgb> passed;
  std::vector<char> asked;
  if (caster_) passed.resize(piece_centre_.size()), asked.assign(piece_centre_.size(), 0);
  const auto evaluate = [&](int b) {
    const Rgb e = beams_[b].irradiance(x, n);
    if (!caster_ || e == Rgb::Zero()) return e;
    const int piece = beam_piece_[b];
    if (!asked[piece]) {
      asked[piece] = 1;
      // From off x's surface to just off the piece, on x's side of it.
      const Vec3& c = piece_centre_[piece];
      const double side = piece_normal_[piece].dot(x - c) > 0 ? 1.0 : -1.0;
      const Vec3 origin = x + offset_ * n;
      const Vec3 leg = c + side * offset_ * piece_normal_[piece] - origin;
      const double length = leg.norm();
      passed[piece] = length > 2 * offset_
                          ? caster_->transmittance({origin, leg / length}, 0.5 * offset_,
                                                   length - offset_, offset_)
                          : Rgb(Rgb::Ones());
    }
    return Rgb(e.cwiseProduct(passed[piece]));
  };
  if (!hierarchy_) {
    for (int b = 0; b < static_cast<int>(beams_.size()); ++b) result.irradiance += evaluate(b);
    result.beams = static_cast<int>(beams_.size());
    return result;
  }
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!may_reach(node, x)) continue;
    if (node.left < 0) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        if (!may_reach(leaf_bounds_[order_[k]], x)) continue;  // each beam's own cone
        result.irradiance += evaluate(order_[k]);
        ++result.beams;
      }
      continue;
    }
    stack[top++] = node.right;
    stack[top++] = node.left;
  }
  return result;
}

}  // namespace rad
