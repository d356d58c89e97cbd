#include "localpass/hemisphere_gather.h"

#include <algorithm>
#include <numeric>

#include "hemisphere/visible_surface.h"
#include "scene/error.h"

namespace rad {

HemisphereGatherer::HemisphereGatherer(const Scene& scene) : HemisphereGatherer(scene, {}) {
  for (const Polygon& p : scene.polygons) exitance_.push_back(scene.materials[p.material].emission);
}

HemisphereGatherer::HemisphereGatherer(const Scene& scene, std::vector<Rgb> exitance)
    : scene_(scene), exitance_(std::move(exitance)) {
  if (!exitance_.empty() && exitance_.size() != scene.polygons.size()) {
    throw Error("hemisphere gather: " + std::to_string(exitance_.size()) + " exitances for " +
                std::to_string(scene.polygons.size()) + " polygons");
  }
  // Concave polygons become triangles in their own plane: every projected piece is convex.
  for (size_t i = 0; i < scene.polygons.size(); ++i) {
    const Polygon& p = scene.polygons[i];
    for (const auto& t : triangulate(project_to_plane(p.vertices, p.normal))) {
      Triangle tri{static_cast<int>(i), p.vertices[t[0]], p.vertices[t[1]], p.vertices[t[2]], Vec3::Zero(), 0};
      tri.centre = (tri.a + tri.b + tri.c) / 3;
      tri.radius = std::max({(tri.a - tri.centre).norm(), (tri.b - tri.centre).norm(), (tri.c - tri.centre).norm()});
      triangles_.push_back(tri);
    }
  }
  in_plane_ = 1e-12 * scene.bounds().diagonal();
}

GatherResult HemisphereGatherer::gather(const Vec3& x, const Vec3& n, bool keep_fragments) const {
  // Front to back by a lower bound on distance (ties by index): far triangles then stop at
  // their first depth test. The order never changes the result, only the work.
  std::vector<std::pair<double, int>> order;
  order.reserve(triangles_.size());
  for (size_t t = 0; t < triangles_.size(); ++t) {
    const Triangle& tri = triangles_[t];
    order.emplace_back(std::max(0.0, (tri.centre - x).norm() - tri.radius), static_cast<int>(t));
  }
  std::sort(order.begin(), order.end());

  hemi::VisibleSurface visible;
  for (const auto& [distance, t] : order) {
    const Triangle& tri = triangles_[t];
    const Polygon& polygon = scene_.polygons[tri.polygon];
    const double offset = polygon.normal.dot(tri.a - x);
    if (std::abs(offset) <= in_plane_) continue;  // x in its plane: no solid angle
    const auto clipped = hemi::clip_to_upper_halfspace({tri.a - x, tri.b - x, tri.c - x}, n);
    if (clipped.size() < 3) continue;
    const hemi::SphericalPolygon region(clipped);
    if (region.empty()) continue;
    visible.insert(hemi::Occluder{tri.polygon, polygon.normal, offset}, region);
  }

  GatherResult result;
  for (const hemi::Fragment& f : visible.fragments()) {
    const double ff = f.region.form_factor(n);
    const Polygon& polygon = scene_.polygons[f.id];
    // The receiver sees the front when it lies in front of the plane.
    const bool front = polygon.normal.dot(x - polygon.vertices.front()) > 0;
    result.covered += ff;
    if (front) result.irradiance += ff * exitance_[f.id];
    if (keep_fragments) result.fragments.push_back({f.id, ff, front, f.region.vertices()});
  }
  return result;
}

}  // namespace rad
