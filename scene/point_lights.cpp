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
  if (!m.is_glossy() || cos_out == 0) return Rgb::Zero();
  // Reflected: lights on out's side, off the front. Passed through a roughened pane: lights
  // on the other side, from either side, the lobe about the light's own direction.
  const bool front = cos_out > 0;
  Rgb reflected = Rgb::Zero(), passed_on = Rgb::Zero();
  for (const PointLight& light : scene.lights) {
    const double side = n.dot(light.position - x);
    const bool same_side = (side > 0) == front;
    const bool reflects = same_side && front && m.is_glossy_mirror();
    const bool passes = !same_side && m.is_glossy_pane();
    if (!(reflects || passes) || side == 0) continue;
    const Vec3 origin = x + (side > 0 ? offset : -offset) * n;
    const Vec3 to = light.position - origin;
    const double r = to.norm();
    const Vec3 w = to / r;
    const double cos_in = std::abs(n.dot(w));
    const Vec3 centre = reflects ? reflect(-w, shading) : Vec3(-w);
    const double phi = std::atan2(out.cross(centre).norm(), out.dot(centre));
    const double lobe = gaussian_lobe(phi, m.gloss);
    if (!(lobe > 0)) continue;
    const Rgb through = caster.transmittance({origin, w}, 0.5 * offset, r - offset, offset);
    const Rgb l =
        light.intensity.cwiseProduct(through) * (lobe * cos_in / (r * r * std::abs(cos_out)));
    (reflects ? reflected : passed_on) += l;
  }
  return (m.specular.cwiseProduct(reflected) + m.glossy_transmittance.cwiseProduct(passed_on)) *
         std::numbers::pi;
}

}  // namespace rad
