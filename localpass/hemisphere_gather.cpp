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
  // Every projected piece must be convex: convex polygons stay whole (fewer fragments and BSP
  // planes), concave ones become triangles in their own plane.
  auto add_piece = [&](int polygon, std::vector<Vec3> vertices) {
    Vec3 centre = Vec3::Zero();
    for (const Vec3& v : vertices) centre += v;
    centre /= static_cast<double>(vertices.size());
    double radius = 0;
    for (const Vec3& v : vertices) radius = std::max(radius, (v - centre).norm());
    pieces_.push_back({polygon, std::move(vertices), centre, radius});
  };
  for (size_t i = 0; i < scene.polygons.size(); ++i) {
    const Polygon& p = scene.polygons[i];
    const std::vector<Vec2> flat = project_to_plane(p.vertices, p.normal);
    const double orientation = signed_area_2d(flat) > 0 ? 1 : -1;
    bool convex = true;
    for (size_t k = 0; k < flat.size() && convex; ++k) {
      const Vec2 e0 = flat[(k + 1) % flat.size()] - flat[k], e1 = flat[(k + 2) % flat.size()] - flat[(k + 1) % flat.size()];
      convex = orientation * (e0.x() * e1.y() - e0.y() * e1.x()) >= 0;
    }
    if (convex) {
      add_piece(static_cast<int>(i), p.vertices);
      continue;
    }
    for (const auto& t : triangulate(flat)) add_piece(static_cast<int>(i), {p.vertices[t[0]], p.vertices[t[1]], p.vertices[t[2]]});
  }
  in_plane_ = 1e-12 * scene.bounds().diagonal();
}

GatherResult HemisphereGatherer::gather(const Vec3& x, const Vec3& n, bool keep_fragments) const {
  // Front to back by a lower bound on distance (ties by index): far triangles then stop at
  // their first depth test. The order never changes the result, only the work.
  std::vector<std::pair<double, int>> order;
  order.reserve(pieces_.size());
  for (size_t k = 0; k < pieces_.size(); ++k) {
    order.emplace_back(std::max(0.0, (pieces_[k].centre - x).norm() - pieces_[k].radius), static_cast<int>(k));
  }
  std::sort(order.begin(), order.end());

  hemi::VisibleSurface visible;
  std::vector<Vec3> relative;
  for (const auto& [distance, k] : order) {
    const Piece& piece = pieces_[k];
    const Polygon& polygon = scene_.polygons[piece.polygon];
    const double offset = polygon.normal.dot(piece.vertices.front() - x);
    if (std::abs(offset) <= in_plane_) continue;  // x in its plane: no solid angle
    relative.clear();
    for (const Vec3& v : piece.vertices) relative.push_back(v - x);
    const auto clipped = hemi::clip_to_upper_halfspace(relative, n);
    if (clipped.size() < 3) continue;
    const hemi::SphericalPolygon region(clipped);
    if (region.empty()) continue;
    visible.insert(hemi::Occluder{piece.polygon, polygon.normal, offset}, region);
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
