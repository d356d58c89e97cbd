#include "hemisphere/hemisphere_gatherer.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "geometry/clip.h"
#include "geometry/plane.h"
#include "hemisphere/blocker_surface.h"
#include "hemisphere/visible_surface.h"

namespace rad {

/// ExactGatherSession of the hemisphere method: one visible-surface structure that grows.
class HemisphereGatherer::Session final : public ExactGatherSession {
 public:
  Session(const HemisphereGatherer& gatherer, const Vec3& x, const Vec3& n)
      : gatherer_(gatherer),
        x_(x),
        n_(n),
        added_(gatherer.faces_.size(), 0),
        radiating_(gatherer.faces_.size(), 0) {}

  ExactGatherTotal step(const std::vector<int>& radiating,
                        const std::vector<int>& occluders) override {
    // Project what is new, nearest first.
    std::vector<std::pair<double, int>> order;
    for (const std::vector<int>* list : {&radiating, &occluders}) {
      for (const int k : *list) {
        if (added_[k]) continue;
        added_[k] = 1;
        ++added_count_;
        order.emplace_back(gatherer_.distance_bound(k, x_), k);
      }
    }
    std::sort(order.begin(), order.end());
    for (const auto& [distance, k] : order) gatherer_.project(k, x_, n_, &visible_);
    for (const int k : radiating) radiating_[k] = 1;

    // Every visible fragment of a radiating face, again: a later face may have hidden part of
    // an earlier one.
    ExactGatherTotal total;
    double covered = 0;
    for (const hemi::Fragment& f : visible_.fragments()) {
      if (!radiating_[f.id]) continue;
      const EmittingFace& face = gatherer_.faces_[f.id];
      const double ff = f.region.form_factor(n_);
      covered += ff;
      if (is_in_front_of(x_, face.vertices.front(), face.normal))
        total.irradiance += ff * face.exitance;
    }
    total.covered = covered;
    return total;
  }
  int projected() const override { return added_count_; }

 private:
  const HemisphereGatherer& gatherer_;
  Vec3 x_, n_;
  std::vector<char> added_, radiating_;
  int added_count_ = 0;
  hemi::VisibleSurface visible_;
};

HemisphereGatherer::HemisphereGatherer(std::vector<EmittingFace> faces, const Tolerance& tolerance)
    : faces_(std::move(faces)), in_plane_(tolerance.in_plane) {
  for (const EmittingFace& f : faces_) {
    if (f.vertices.size() < 3) {
      throw std::invalid_argument("hemisphere gather: a face of polygon " +
                                  std::to_string(f.polygon) + " has " +
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
}

double HemisphereGatherer::distance_bound(int k, const Vec3& x) const {
  return std::max(0.0, (centres_[k] - x).norm() - radii_[k]);
}

HemisphereGather HemisphereGatherer::gather(const Vec3& x, const Vec3& n,
                                            bool keep_fragments) const {
  std::vector<std::pair<double, int>> order;
  order.reserve(faces_.size());
  for (size_t k = 0; k < faces_.size(); ++k)
    order.emplace_back(distance_bound(static_cast<int>(k), x), static_cast<int>(k));
  std::sort(order.begin(), order.end());

  hemi::VisibleSurface visible;
  for (const auto& [distance, k] : order) project(k, x, n, &visible);

  HemisphereGather result;
  for (const hemi::Fragment& f : visible.fragments()) {
    const double ff = f.region.form_factor(n);
    const EmittingFace& face = faces_[f.id];
    const bool front = is_in_front_of(x, face.vertices.front(), face.normal);
    result.covered += ff;
    if (front) result.irradiance += ff * face.exitance;
    if (keep_fragments)
      result.fragments.push_back(
          {face.polygon, ff, front, {f.region.vertices().begin(), f.region.vertices().end()}});
  }
  return result;
}

std::unique_ptr<ExactGatherSession> HemisphereGatherer::start(const Vec3& x, const Vec3& n) const {
  return std::make_unique<Session>(*this, x, n);
}

void HemisphereGatherer::project(int k, const Vec3& x, const Vec3& n, void* visible) const {
  const EmittingFace& face = faces_[k];
  // Occluder id = face index: faces are ordered by polygon, so coplanar overlapping polygons
  // resolve to the lower polygon index, as in the vertex tracer.
  const auto p = project_onto_hemisphere(k, face.vertices, face.normal, x, n, in_plane_);
  if (p) static_cast<hemi::VisibleSurface*>(visible)->insert(p->occluder, p->region);
}

}  // namespace rad
