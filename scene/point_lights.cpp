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

PointLightIrradiance::PointLightIrradiance(const RayCaster& caster, double offset)
    : caster_(caster), offset_(offset) {
  const Scene& scene = caster.scene();
  in_plane_ = scene.tolerance().in_plane;
  if (scene.lights.empty() || scene.mirror_depth == 0) return;
  pieces_ = mirror_pieces(scene);
  std::erase_if(pieces_, [&](const MirrorPiece& piece) {
    return scene.materials[scene.polygons[piece.polygon].material].is_glossy_mirror();
  });
  for (const std::vector<int>& chain : mirror_chains(pieces_, scene.mirror_depth, in_plane_)) {
    for (const PointLight& light : scene.lights) {
      if (!(pieces_[chain.back()].height(light.position) > in_plane_)) continue;
      Image image{light.position, light.intensity, chain};
      for (auto j = chain.rbegin(); j != chain.rend(); ++j) {
        image.position = pieces_[*j].reflect(image.position);
        image.intensity = image.intensity.cwiseProduct(pieces_[*j].specular);
      }
      images_.push_back(std::move(image));
    }
  }
}

Rgb PointLightIrradiance::operator()(const Vec3& x, const Vec3& n) const {
  const Scene& scene = caster_.scene();
  if (scene.lights.empty()) return Rgb::Zero();
  Rgb h = point_light_irradiance(scene, caster_, x, n, offset_);
  for (const Image& image : images_) h += by_image(image, x, n);
  return h;
}

Rgb PointLightIrradiance::by_image(const Image& image, const Vec3& x, const Vec3& n) const {
  if (!(pieces_[image.chain.front()].height(x) > in_plane_)) return Rgb::Zero();
  const Rgb unoccluded = PointLight{image.position, image.intensity}.unoccluded_irradiance(x, n);
  if (unoccluded == Rgb::Zero()) return Rgb::Zero();
  // The unfolded segment, started as the straight one (off x's surface, half an offset back),
  // bent at each mirror: its crossing p of piece j's plane is where the path meets piece j,
  // and reflecting the target by piece j leaves the image of the light in the mirrors after j.
  const Vec3 w = (image.position - x).normalized();
  Vec3 from = x + offset_ * n - 0.5 * offset_ * w, target = image.position;
  double skip = 1.5 * offset_;  // near x the first leg skips what the straight one skips
  Rgb passed = Rgb::Ones();
  const auto leg = [&](const Vec3& to) {
    const Vec3 d = to - from;
    const double distance = d.norm();
    if (distance > skip + offset_)
      passed = passed.cwiseProduct(
          caster_.transmittance({from, d / distance}, skip, distance - offset_, offset_));
    skip = offset_;  // later legs start on a mirror: it is not in their way
  };
  for (const int j : image.chain) {
    const MirrorPiece& m = pieces_[j];
    const double hf = m.height(from), ht = m.height(target);
    if (!(hf > 0 && ht < 0)) return Rgb::Zero();
    const Vec3 p = from + (hf / (hf - ht)) * (target - from);
    if (!m.contains(p)) return Rgb::Zero();
    leg(p);
    if (passed == Rgb::Zero()) return Rgb::Zero();
    from = p;
    target = m.reflect(target);
  }
  leg(target);  // the light itself, now that every mirror has reflected its image back
  return unoccluded.cwiseProduct(passed);
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
    const double phi = angle_between(out, centre);
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
