#include "scene/point_lights.h"

namespace rad {

Rgb point_light_irradiance(const Scene& scene, const RayCaster& caster, const Vec3& x,
                           const Vec3& n, double offset) {
  Rgb h = Rgb::Zero();
  for (const PointLight& light : scene.lights) {
    const Rgb unoccluded = light.unoccluded_irradiance(x, n);
    if (unoccluded == Rgb::Zero()) continue;
    const Vec3 to = light.position - x;
    const Vec3 w = to.normalized();
    const Vec3 origin = x + offset * n - 0.5 * offset * w;
    const Vec3 leg = light.position - origin;
    const double distance = leg.norm();
    const Rgb passed =
        caster.transmittance({origin, leg / distance}, 1.5 * offset, distance - offset, offset);
    h += unoccluded.cwiseProduct(passed);
  }
  return h;
}

}  // namespace rad
