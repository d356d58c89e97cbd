#include "localpass/hemisphere_gather.h"

#include <algorithm>

#include "hemisphere/visible_surface.h"
#include "scene/error.h"

namespace rad {

HemisphereGatherer::HemisphereGatherer(const Scene& scene) : HemisphereGatherer(scene, faces_from_polygons(scene)) {}

HemisphereGatherer::HemisphereGatherer(const Scene& scene, std::vector<Rgb> exitance)
    : HemisphereGatherer(scene, faces_from_polygons(scene, std::move(exitance))) {}

HemisphereGatherer::HemisphereGatherer(const Scene& scene, std::vector<EmittingFace> faces)
    : scene_(scene), faces_(std::move(faces)) {
  for (const EmittingFace& f : faces_) {
    if (f.polygon < 0 || f.polygon >= static_cast<int>(scene.polygons.size()) || f.vertices.size() < 3) {
      throw Error("hemisphere gather: a face refers to polygon " + std::to_string(f.polygon) + " or has " +
                  std::to_string(f.vertices.size()) + " vertices");
    }
    Vec3 centre = Vec3::Zero();
    for (const Vec3& v : f.vertices) centre += v;
    centre /= static_cast<double>(f.vertices.size());
    double radius = 0;
    for (const Vec3& v : f.vertices) radius = std::max(radius, (v - centre).norm());
    centres_.push_back(centre);
    radii_.push_back(radius);
  }
  in_plane_ = 1e-12 * scene.bounds().diagonal();
}

GatherResult HemisphereGatherer::gather(const Vec3& x, const Vec3& n, bool keep_fragments) const {
  // Front to back by a lower bound on distance (ties by index): far faces then stop at their
  // first depth test. The order never changes the result, only the work.
  std::vector<std::pair<double, int>> order;
  order.reserve(faces_.size());
  for (size_t k = 0; k < faces_.size(); ++k) {
    order.emplace_back(std::max(0.0, (centres_[k] - x).norm() - radii_[k]), static_cast<int>(k));
  }
  std::sort(order.begin(), order.end());

  hemi::VisibleSurface visible;
  for (const auto& [distance, k] : order) project(k, x, n, &visible);

  GatherResult result;
  for (const hemi::Fragment& f : visible.fragments()) {
    const double ff = f.region.form_factor(n);
    const EmittingFace& face = faces_[f.id];
    const Polygon& polygon = scene_.polygons[face.polygon];
    // The receiver sees the front when it lies in front of the plane.
    const bool front = polygon.normal.dot(x - polygon.vertices.front()) > 0;
    result.covered += ff;
    if (front) result.irradiance += ff * face.exitance;
    if (keep_fragments) result.fragments.push_back({face.polygon, ff, front, f.region.vertices()});
  }
  return result;
}

void HemisphereGatherer::project(int k, const Vec3& x, const Vec3& n, void* visible) const {
  const EmittingFace& face = faces_[k];
  const Polygon& polygon = scene_.polygons[face.polygon];
  const double offset = polygon.normal.dot(face.vertices.front() - x);
  if (std::abs(offset) <= in_plane_) return;  // x in its plane: no solid angle
  std::vector<Vec3> relative;
  for (const Vec3& v : face.vertices) relative.push_back(v - x);
  const auto clipped = hemi::clip_to_upper_halfspace(relative, n);
  if (clipped.size() < 3) return;
  const hemi::SphericalPolygon region(clipped);
  if (region.empty()) return;
  // Occluder id = face index: faces are ordered by polygon, so coplanar overlapping polygons
  // resolve to the lower polygon index, as in the vertex tracer.
  static_cast<hemi::VisibleSurface*>(visible)->insert(hemi::Occluder{k, polygon.normal, offset}, region);
}

HemisphereGatherer::Session::Session(const HemisphereGatherer& gatherer, const Vec3& x, const Vec3& n)
    : gatherer_(gatherer), x_(x), n_(n), added_(gatherer.faces_.size(), 0),
      visible_(std::make_shared<hemi::VisibleSurface>()) {}

void HemisphereGatherer::Session::add(const std::vector<int>& faces) {
  std::vector<std::pair<double, int>> order;
  for (const int k : faces) {
    if (added_[k]) continue;
    added_[k] = 1;
    ++added_count_;
    order.emplace_back(std::max(0.0, (gatherer_.centres_[k] - x_).norm() - gatherer_.radii_[k]), k);
  }
  std::sort(order.begin(), order.end());
  for (const auto& [distance, k] : order) gatherer_.project(k, x_, n_, visible_.get());
}

Rgb HemisphereGatherer::Session::irradiance(const std::vector<char>& radiating, double* covered) const {
  Rgb sum = Rgb::Zero();
  double ff_sum = 0;
  for (const hemi::Fragment& f : static_cast<const hemi::VisibleSurface*>(visible_.get())->fragments()) {
    if (!radiating[f.id]) continue;
    const EmittingFace& face = gatherer_.faces_[f.id];
    const double ff = f.region.form_factor(n_);
    ff_sum += ff;
    const Polygon& polygon = gatherer_.scene_.polygons[face.polygon];
    if (polygon.normal.dot(x_ - polygon.vertices.front()) > 0) sum += ff * face.exitance;
  }
  if (covered) *covered = ff_sum;
  return sum;
}

}  // namespace rad
