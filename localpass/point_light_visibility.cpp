#include "localpass/point_light_visibility.h"

#include <cmath>

namespace rad {

PointLightVisibility::PointLightVisibility(const Scene& scene)
    : scene_(scene), in_plane_(scene.tolerance().in_plane) {
  planes_.reserve(scene.polygons.size());
  for (const Polygon& p : scene.polygons) {
    Plane plane{PlaneFrame(p.vertices.front(), p.normal), p.normal.dot(p.vertices.front()), {}, {}};
    for (const Vec3& vertex : p.vertices) plane.outline.push_back(plane.frame.to_2d(vertex));
    // A refracting interface is opaque to straight lines (scene/material.h): transmittance 0.
    plane.transmittance = scene.materials[p.material].transmittance;
    planes_.push_back(std::move(plane));
  }
}

Rgb PointLightVisibility::irradiance(const Vec3& x, const Vec3& n,
                                     std::span<const int> candidates) const {
  Rgb h = Rgb::Zero();
  for (const PointLight& light : scene_.lights) {
    const Rgb unoccluded = light.unoccluded_irradiance(x, n);
    if (unoccluded == Rgb::Zero()) continue;
    Rgb passed = Rgb::Ones();
    for (const int i : candidates) {
      const Plane& p = planes_[i];
      const Vec3& normal = p.frame.n;
      const double sx = normal.dot(x) - p.offset, sl = normal.dot(light.position) - p.offset;
      if (!(std::abs(sx) > in_plane_ && std::abs(sl) > in_plane_) || (sx > 0) == (sl > 0))
        continue;  // edge-on to x, the light on its plane, or both on one side
      const Vec3 meet = x + (sx / (sx - sl)) * (light.position - x);
      if (!contains_2d(p.outline, p.frame.to_2d(meet))) continue;
      passed = passed.cwiseProduct(p.transmittance);
      if (passed == Rgb::Zero()) break;
    }
    h += unoccluded.cwiseProduct(passed);
  }
  return h;
}

}  // namespace rad
