#include "radiosity/solution_faces.h"

#include <algorithm>

#include "scene/error.h"
#include "scene/polygon_faces.h"

namespace rad {

std::vector<EmittingFace> faces_from_solution(const Scene& scene, const Solution& solution) {
  const double tolerance = scene.tolerance().pad;
  std::vector<EmittingFace> faces;
  for (const int leaf : solution.leaves()) {
    const Element& e = solution.elements[leaf];
    if (e.polygon < 0 || e.polygon >= static_cast<int>(scene.polygons.size())) {
      throw Error("gather: element " + std::to_string(leaf) + " refers to polygon " +
                  std::to_string(e.polygon) + " of a scene with " +
                  std::to_string(scene.polygons.size()));
    }
    const Polygon& p = scene.polygons[e.polygon];
    EmittingFace face{e.polygon, e.corners, e.radiosity,
                      {},        p.normal,  scene.materials[p.material].transmittance};
    const size_t n = e.corners.size();
    for (size_t k = 0; k < n; ++k) {
      // On the boundary when both ends lie on one polygon edge.
      const Vec3& a = e.corners[k];
      const Vec3& b = e.corners[(k + 1) % n];
      bool boundary = false;
      for (size_t j = 0; j < p.vertices.size() && !boundary; ++j) {
        const Vec3& pa = p.vertices[j];
        const Vec3& pb = p.vertices[(j + 1) % p.vertices.size()];
        boundary = point_segment_distance(a, pa, pb) <= tolerance &&
                   point_segment_distance(b, pa, pb) <= tolerance;
      }
      face.on_boundary.push_back(boundary);
    }
    orient_counter_clockwise(face);
    faces.push_back(std::move(face));
  }
  std::stable_sort(faces.begin(), faces.end(), [](const EmittingFace& a, const EmittingFace& b) {
    return a.polygon < b.polygon;
  });
  return faces;
}

}  // namespace rad
