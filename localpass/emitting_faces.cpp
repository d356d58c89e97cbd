#include "localpass/emitting_faces.h"

#include <algorithm>

#include "scene/error.h"
#include "scene/polygon.h"

namespace rad {
namespace {

bool is_convex(const std::vector<Vec2>& flat) {
  const double orientation = signed_area_2d(flat) > 0 ? 1 : -1;
  const size_t n = flat.size();
  for (size_t k = 0; k < n; ++k) {
    const Vec2 e0 = flat[(k + 1) % n] - flat[k], e1 = flat[(k + 2) % n] - flat[(k + 1) % n];
    if (orientation * (e0.x() * e1.y() - e0.y() * e1.x()) < 0) return false;
  }
  return true;
}

/// Distance from p to segment ab.
double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

/// Makes the face counter-clockwise about `normal` (triangulation and element corners may come
/// either way round); edge flags follow their edges.
void orient(EmittingFace& face, const Vec3& normal) {
  if (newell_vector(face.vertices).dot(normal) >= 0) return;
  const size_t n = face.vertices.size();
  std::reverse(face.vertices.begin(), face.vertices.end());
  // Reversed edge j joins old vertices n-1-j and n-2-j: it is old edge n-2-j (mod n).
  std::vector<bool> flags(n);
  for (size_t j = 0; j < n; ++j) flags[j] = face.on_boundary[(2 * n - 2 - j) % n];
  face.on_boundary = std::move(flags);
}

}  // namespace

std::vector<EmittingFace> faces_from_polygons(const Scene& scene, std::vector<Rgb> exitance) {
  if (exitance.empty()) {
    for (const Polygon& p : scene.polygons) exitance.push_back(scene.materials[p.material].emission);
  }
  if (exitance.size() != scene.polygons.size()) {
    throw Error("gather: " + std::to_string(exitance.size()) + " exitances for " +
                std::to_string(scene.polygons.size()) + " polygons");
  }
  std::vector<EmittingFace> faces;
  for (size_t i = 0; i < scene.polygons.size(); ++i) {
    const Polygon& p = scene.polygons[i];
    const std::vector<Vec2> flat = project_to_plane(p.vertices, p.normal);
    const int polygon = static_cast<int>(i);
    if (is_convex(flat)) {
      faces.push_back({polygon, p.vertices, exitance[i], std::vector<bool>(p.vertices.size(), true)});
      orient(faces.back(), p.normal);
      continue;
    }
    const int n = static_cast<int>(p.vertices.size());
    for (const auto& t : triangulate(flat)) {
      EmittingFace face{polygon, {p.vertices[t[0]], p.vertices[t[1]], p.vertices[t[2]]}, exitance[i], {}};
      // A triangle edge is a polygon edge when its corners are consecutive polygon vertices.
      for (int e = 0; e < 3; ++e) {
        const int a = t[e], b = t[(e + 1) % 3];
        face.on_boundary.push_back((b - a + n) % n == 1 || (a - b + n) % n == 1);
      }
      orient(face, p.normal);
      faces.push_back(std::move(face));
    }
  }
  return faces;
}

std::vector<EmittingFace> faces_from_solution(const Scene& scene, const Solution& solution) {
  const double tolerance = 1e-9 * scene.bounds().diagonal();
  std::vector<EmittingFace> faces;
  for (const int leaf : solution.leaves()) {
    const Element& e = solution.elements[leaf];
    if (e.polygon < 0 || e.polygon >= static_cast<int>(scene.polygons.size())) {
      throw Error("gather: element " + std::to_string(leaf) + " refers to polygon " + std::to_string(e.polygon) +
                  " of a scene with " + std::to_string(scene.polygons.size()));
    }
    const Polygon& p = scene.polygons[e.polygon];
    EmittingFace face{e.polygon, e.corners, e.radiosity, {}};
    const size_t n = e.corners.size();
    for (size_t k = 0; k < n; ++k) {
      // On the boundary when both ends lie on one polygon edge.
      const Vec3& a = e.corners[k];
      const Vec3& b = e.corners[(k + 1) % n];
      bool boundary = false;
      for (size_t j = 0; j < p.vertices.size() && !boundary; ++j) {
        const Vec3& pa = p.vertices[j];
        const Vec3& pb = p.vertices[(j + 1) % p.vertices.size()];
        boundary = segment_distance(a, pa, pb) <= tolerance && segment_distance(b, pa, pb) <= tolerance;
      }
      face.on_boundary.push_back(boundary);
    }
    orient(face, p.normal);
    faces.push_back(std::move(face));
  }
  std::stable_sort(faces.begin(), faces.end(),
                   [](const EmittingFace& a, const EmittingFace& b) { return a.polygon < b.polygon; });
  return faces;
}

}  // namespace rad
