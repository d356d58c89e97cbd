#pragma once
/// Seeded random polygon scenes for differential tests of the exact gatherers: polygons at
/// random positions, sizes and orientations (convex and concave, interpenetrating at will) over a
/// receiving floor, some emitting, plus families built to be degenerate for vertex tracing.
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "scene/polygon_faces.h"
#include "tests/scene_builder.h"

namespace rad::test {

struct ProbeSite {
  Vec3 x, n;
};

struct RandomScene {
  Scene scene;
  std::vector<ProbeSite> sites;
};

class RandomSceneMaker {
 public:
  explicit RandomSceneMaker(uint64_t seed) : rng_(seed) {}

  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  int integer(int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng_); }
  Vec3 unit() {
    std::normal_distribution<double> g;
    return Vec3(g(rng_), g(rng_), g(rng_)).normalized();
  }
  /// A unit vector perpendicular to n.
  Vec3 perpendicular(const Vec3& n) {
    Vec3 t;
    do t = unit().cross(n);
    while (t.norm() < 1e-3);
    return t.normalized();
  }

  /// A convex polygon (3..6 vertices, jittered regular) or a concave one (a star or an L),
  /// centred at c in the plane with normal n.
  std::vector<Vec3> polygon(const Vec3& c, const Vec3& n, double size) {
    const Vec3 u = perpendicular(n), v = n.cross(u);
    std::vector<Vec3> out;
    const int kind = integer(0, 3);
    if (kind <= 1) {
      const int count = integer(3, 6);
      const double phase = uniform(0, 2 * std::numbers::pi);
      for (int i = 0; i < count; ++i) {
        const double a = phase + 2 * std::numbers::pi * (i + uniform(-0.25, 0.25)) / count;
        const double r = size * uniform(0.6, 1.0);
        out.push_back(c + r * (std::cos(a) * u + std::sin(a) * v));
      }
    } else if (kind == 2) {
      const int count = 2 * integer(3, 5);
      for (int i = 0; i < count; ++i) {
        const double a = 2 * std::numbers::pi * i / count;
        const double r = size * (i % 2 == 0 ? 1.0 : uniform(0.3, 0.6));
        out.push_back(c + r * (std::cos(a) * u + std::sin(a) * v));
      }
    } else {
      const double s = size, t = size * uniform(0.3, 0.7);
      for (const auto& [a, b] : std::vector<std::pair<double, double>>{
               {-s, -s}, {s, -s}, {s, -s + t}, {-s + t, -s + t}, {-s + t, s}, {-s, s}}) {
        out.push_back(c + a * u + b * v);
      }
    }
    return out;
  }

  /// The general family: a floor at z = 0 and 2..7 random polygons above it.
  RandomScene random_scene() {
    SceneBuilder b;
    std::vector<int> materials;
    materials.push_back(b.material("grey", Rgb::Constant(0.5), Rgb::Zero()));
    for (int i = 0; i < 3; ++i)
      materials.push_back(b.material("lamp" + std::to_string(i), Rgb::Zero(),
                                     Rgb(uniform(0.2, 2), uniform(0.2, 2), uniform(0.2, 2))));
    b.rectangle(-2, 2, -2, 2, 0, false, materials[0]);
    const int count = integer(2, 7);
    bool any_emitter = false;
    for (int i = 0; i < count; ++i) {
      const bool emitter = integer(0, 2) == 0 || (i == count - 1 && !any_emitter);
      any_emitter = any_emitter || emitter;
      const Vec3 c(uniform(-1, 1), uniform(-1, 1), uniform(0.1, 1.5));
      b.polygon(polygon(c, unit(), uniform(0.1, 0.8)),
                emitter ? materials[integer(1, 3)] : materials[0]);
    }
    RandomScene out{b.scene(), {}};
    for (int i = 0; i < 4; ++i)
      out.sites.push_back({Vec3(uniform(-1.5, 1.5), uniform(-1.5, 1.5), 0), Vec3::UnitZ()});
    // Points on the polygons themselves, on their front side, facing out.
    for (size_t p = 1; p < out.scene.polygons.size() && out.sites.size() < 6; ++p) {
      const Polygon& poly = out.scene.polygons[p];
      const double w0 = uniform(0, 1), w1 = uniform(0, 1 - w0);
      const Vec3 x = poly.vertices[0] + w0 * (poly.vertices[1] - poly.vertices[0]) +
                     w1 * (poly.vertices[2] - poly.vertices[0]);
      out.sites.push_back({x, poly.normal});
    }
    return out;
  }

  /// Families built to be conjunctive for vertex tracing, seen from the origin (normal +z) where
  /// the coincidences are exact up to rounding (plus two more floor points):
  enum class Conjunction {
    three_edges,      ///< three edges at different depths through one apparent point
    vertex_behind,    ///< polygon vertices exactly behind one another
    collinear_edges,  ///< edges on one 3D line, and edges in one plane through the origin
    coplanar,         ///< coplanar polygons, overlapping and adjacent
    vertex_on_edge,   ///< a vertex on another polygon's edge, in 3D and in projection
  };
  static constexpr int kConjunctions = 5;

  RandomScene conjunctive_scene(Conjunction kind) {
    SceneBuilder b;
    const int grey = b.material("grey", Rgb::Constant(0.5), Rgb::Zero());
    std::vector<int> lamps;
    for (int i = 0; i < 3; ++i)
      lamps.push_back(b.material("lamp" + std::to_string(i), Rgb::Zero(),
                                 Rgb(uniform(0.2, 2), uniform(0.2, 2), uniform(0.2, 2))));
    const auto material = [&](int i) {
      return i == 0 || integer(0, 1) == 0 ? lamps[integer(0, 2)] : grey;
    };
    b.rectangle(-3, 3, -3, 3, -0.01, false, grey);
    // The shared apparent point's direction, well above the horizon.
    Vec3 w;
    do w = unit();
    while (w.z() < 0.3);
    const auto triangle_with_edge_through = [&](const Vec3& p, int m) {
      const Vec3 n = unit(), e = perpendicular(n), f = n.cross(e);
      b.polygon({p - uniform(0.1, 0.5) * e, p + uniform(0.1, 0.5) * e,
                 p + uniform(-0.3, 0.3) * e + uniform(0.1, 0.5) * f},
                m);
    };
    const auto triangle_with_vertex_at = [&](const Vec3& p, int m) {
      const Vec3 n = unit(), e = perpendicular(n), f = n.cross(e);
      const double a = uniform(0, 2 * std::numbers::pi), span = uniform(0.3, 2.5);
      const double r1 = uniform(0.1, 0.5), r2 = uniform(0.1, 0.5);
      b.polygon({p, p + r1 * (std::cos(a) * e + std::sin(a) * f),
                 p + r2 * (std::cos(a + span) * e + std::sin(a + span) * f)},
                m);
    };
    switch (kind) {
      case Conjunction::three_edges:
        for (int i = 0; i < 3; ++i) triangle_with_edge_through(uniform(0.4, 2.0) * w, material(i));
        break;
      case Conjunction::vertex_behind:
        for (int i = 0; i < 3; ++i) triangle_with_vertex_at(uniform(0.4, 2.0) * w, material(i));
        triangle_with_edge_through(uniform(0.4, 2.0) * w, material(3));
        break;
      case Conjunction::collinear_edges: {
        // Two triangles on one 3D line (overlapping segments), in different planes...
        const Vec3 p = uniform(0.5, 1.5) * w, dir = perpendicular(w);
        const Vec3 q = p + uniform(0.3, 0.8) * dir;
        const Vec3 side = perpendicular(dir);
        b.polygon({p, q, p + 0.5 * (q - p) + uniform(0.2, 0.5) * side}, material(0));
        const Vec3 side2 = (side + uniform(0.3, 1.0) * dir.cross(side)).normalized();
        b.polygon(
            {p + 0.3 * (q - p), p + 1.4 * (q - p), p + 0.8 * (q - p) - uniform(0.2, 0.5) * side2},
            material(1));
        // ...and two polygons whose edges lie in one plane through the origin (collinear seen from
        // it).
        const Vec3 a = uniform(0.5, 1.5) * w, c = a + uniform(0.2, 0.6) * perpendicular(w);
        const double s1 = uniform(0.5, 0.9), s2 = uniform(1.1, 1.6);
        triangle_with_vertex_at(a, material(2));
        b.polygon({s1 * a, s1 * c, s1 * (a + c) / 2 + uniform(0.1, 0.3) * unit()}, material(3));
        b.polygon({s2 * a, s2 * c, s2 * (a + c) / 2 + uniform(0.1, 0.3) * unit()}, material(4));
        break;
      }
      case Conjunction::coplanar: {
        const Vec3 n = unit(), c = uniform(0.5, 1.5) * w;
        const Vec3 u = perpendicular(n), v = n.cross(u);
        const double s = uniform(0.2, 0.5);
        // Overlapping: the lower index shows in both methods.
        b.polygon({c - s * u - s * v, c + s * u - s * v, c + s * u + s * v, c - s * u + s * v},
                  material(0));
        const Vec3 c2 = c + uniform(-s, s) * u + uniform(-s, s) * v;
        b.polygon({c2 - s * u - s * v, c2 + s * u - s * v, c2 + s * u + s * v, c2 - s * u + s * v},
                  material(1));
        // Adjacent, sharing part of an edge (a T-junction across polygons).
        const Vec3 c3 = c + 2 * s * u + uniform(-0.5, 0.5) * s * v;
        b.polygon({c3 - s * u - s * v, c3 + s * u - s * v, c3 + s * u + s * v, c3 - s * u + s * v},
                  material(2));
        break;
      }
      case Conjunction::vertex_on_edge: {
        // In 3D: a vertex of one triangle on the edge of another.
        const Vec3 p = uniform(0.5, 1.5) * w, dir = perpendicular(w);
        const Vec3 a = p - uniform(0.1, 0.5) * dir, c = p + uniform(0.1, 0.5) * dir;
        b.polygon({a, c, p + uniform(0.2, 0.5) * perpendicular(dir)}, material(0));
        triangle_with_vertex_at(p, material(1));
        // In projection: a vertex on the ray through another edge's interior point.
        const Vec3 p2 = uniform(0.5, 1.5) * w;
        triangle_with_edge_through(p2, material(2));
        triangle_with_vertex_at(p2 * uniform(0.5, 0.9), material(3));
        triangle_with_vertex_at(p2 * uniform(1.1, 1.5), material(4));
        break;
      }
    }
    RandomScene out{b.scene(), {{Vec3::Zero(), Vec3::UnitZ()}}};
    for (int i = 0; i < 2; ++i)
      out.sites.push_back({Vec3(uniform(-1, 1), uniform(-1, 1), 0), Vec3::UnitZ()});
    return out;
  }

 private:
  std::mt19937_64 rng_;
};

/// Every polygon of `scene` radiating a seeded exitance, so that occlusion anywhere shows in a
/// gathered value (the culling tests' faces).
inline std::vector<EmittingFace> radiating_faces(const Scene& scene, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.1, 1);
  std::vector<Rgb> exitance;
  for (size_t p = 0; p < scene.polygons.size(); ++p) exitance.emplace_back(u(rng), u(rng), u(rng));
  return faces_from_polygons(scene, exitance);
}

}  // namespace rad::test
