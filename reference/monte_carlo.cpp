#include "reference/monte_carlo.h"

#include <cmath>
#include <numbers>
#include <random>

#include "scene/point_lights.h"
#include "scene/polygon.h"

namespace rad {

MonteCarloGatherer::MonteCarloGatherer(const Scene& scene, const std::vector<EmittingFace>& faces) {
  faces_scene_.materials = scene.materials;
  faces_scene_.mirror_depth = scene.mirror_depth;
  faces_scene_.refraction_depth = scene.refraction_depth;
  faces_scene_.lights = scene.lights;
  for (const EmittingFace& f : faces) {
    const Polygon& parent = scene.polygons[f.polygon];
    Polygon p = parent;
    p.vertices = f.vertices;
    faces_scene_.polygons.push_back(std::move(p));
    exitance_.push_back(f.exitance);
  }
  caster_ = std::make_unique<RayCaster>(faces_scene_);
  offset_ = scene.tolerance().ray_offset;
  lights_ = std::make_unique<PointLightIrradiance>(*caster_, offset_);
}

MonteCarloGatherer::~MonteCarloGatherer() = default;

Rgb MonteCarloGatherer::gather(const Vec3& x, const Vec3& n, int samples, uint64_t seed) const {
  const int strata =
      std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(samples)))));
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + 1);
  std::uniform_real_distribution<double> jitter(0, 1);
  const PlaneFrame frame(Vec3::Zero(), n);
  const Vec3 origin = x + offset_ * n;
  Rgb sum = Rgb::Zero();
  for (int i = 0; i < strata; ++i) {
    for (int j = 0; j < strata; ++j) {
      // Malley's method: uniform on the disk (concentric strata in r^2 and phi), lifted.
      const double r2 = (i + jitter(rng)) / strata,
                   phi = 2 * std::numbers::pi * (j + jitter(rng)) / strata;
      const Vec3 d = frame.cosine_direction(r2, phi);
      // Half an offset back along the ray too, so that no ray starts inside a plane (at a point
      // on an edge the lift along n stays in the neighbour's); what lies that near the point
      // is passed (RayCaster::follow), as the exact gatherers see polygons through x edge-on.
      caster_->follow(
          {origin - 0.5 * offset_ * d, d}, RayCaster::limits_of(faces_scene_), offset_,
          [&](const Hit& hit, const Rgb& weight, int) {
            if (hit.front_facing) sum += weight.cwiseProduct(exitance_[hit.polygon]);
          },
          offset_);
    }
  }
  // Point lights: no ray can hit one (nor its image in a mirror), so their direct light is
  // added as it is (I cos / r^2 through the filters between, straight and by the mirrors'
  // images: scene/point_lights.h), with no noise.
  return (*lights_)(x, n) + sum / static_cast<double>(strata * strata);
}

}  // namespace rad
