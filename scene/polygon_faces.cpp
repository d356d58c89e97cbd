#include "scene/polygon_faces.h"

#include <algorithm>

#include "scene/error.h"
#include "scene/polygon.h"

namespace rad {
void orient_counter_clockwise(EmittingFace& face) {
  if (newell_vector(face.vertices).dot(face.normal) >= 0) return;
  const size_t n = face.vertices.size();
  std::reverse(face.vertices.begin(), face.vertices.end());
  // Reversed edge j joins old vertices n-1-j and n-2-j: it is old edge n-2-j (mod n).
  std::vector<bool> flags(n);
  for (size_t j = 0; j < n; ++j) flags[j] = face.on_boundary[(2 * n - 2 - j) % n];
  face.on_boundary = std::move(flags);
}

std::vector<EmittingFace> faces_from_polygons(const Scene& scene, std::vector<Rgb> exitance) {
  if (exitance.empty()) {
    for (const Polygon& p : scene.polygons)
      exitance.push_back(scene.materials[p.material].emission);
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
      faces.push_back(
          {polygon, p.vertices, exitance[i], std::vector<bool>(p.vertices.size(), true), p.normal});
      faces.back().transmittance = scene.materials[p.material].transmittance;
      orient_counter_clockwise(faces.back());
      continue;
    }
    const int n = static_cast<int>(p.vertices.size());
    for (const auto& t : triangulate(flat)) {
      EmittingFace face{polygon,
                        {p.vertices[t[0]], p.vertices[t[1]], p.vertices[t[2]]},
                        exitance[i],
                        {},
                        p.normal};
      // A triangle edge is a polygon edge when its corners are consecutive polygon vertices.
      for (int e = 0; e < 3; ++e) {
        const int a = t[e], b = t[(e + 1) % 3];
        face.on_boundary.push_back((b - a + n) % n == 1 || (a - b + n) % n == 1);
      }
      face.transmittance = scene.materials[p.material].transmittance;
      orient_counter_clockwise(face);
      faces.push_back(std::move(face));
    }
  }
  return faces;
}

}  // namespace rad
