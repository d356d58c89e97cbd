#include "scene/point_lights.h"

#include <cmath>
#include <numbers>

#include "geometry/glossy_beam.h"
#include "geometry/refraction.h"

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

Rgb glossy_highlight(const Scene& scene, const RayCaster& caster, const Material& m, const Vec3& x,
                     const Vec3& n, const Vec3& shading, const Vec3& out, double offset) {
  const double cos_out = n.dot(out);
  if (!m.is_glossy() || !(cos_out > 0)) return Rgb::Zero();
  Rgb l = Rgb::Zero();
  const Vec3 origin = x + offset * n;
  for (const PointLight& light : scene.lights) {
    const Vec3 to = light.position - origin;
    const double r = to.norm();
    const Vec3 w = to / r;
    const double cos_in = n.dot(w);
    if (!(cos_in > 0)) continue;
    const Vec3 mirrored = reflect(-w, shading);
    const double phi = std::atan2(out.cross(mirrored).norm(), out.dot(mirrored));
    const double lobe = gaussian_lobe(phi, m.gloss);
    if (!(lobe > 0)) continue;
    const Rgb passed = caster.transmittance({origin, w}, 0.5 * offset, r - offset, offset);
    l += light.intensity.cwiseProduct(passed) * (lobe * cos_in / (r * r * cos_out));
  }
  return m.specular.cwiseProduct(l) * std::numbers::pi;
}

}  // namespace rad
