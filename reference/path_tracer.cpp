#include "reference/path_tracer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "geometry/glossy_beam.h"
#include "geometry/refraction.h"
#include "geometry/tolerance.h"
#include "scene/point_lights.h"
#include "scene/polygon.h"
#include "scene/polygon_faces.h"

namespace rad {
namespace {

/// A cosine-weighted direction about n (Malley's method).
Vec3 cosine_direction(const Vec3& n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const double r2 = u(rng), phi = 2 * std::numbers::pi * u(rng);
  return PlaneFrame(Vec3::Zero(), n).cosine_direction(r2, phi);
}

}  // namespace

PathTracer::PathTracer(const Scene& scene, bool interface_reflections)
    : scene_(scene),
      caster_(scene),
      offset_(scene.tolerance().ray_offset),
      limits_(RayCaster::limits_of(scene)),
      lights_(caster_, offset_) {
  limits_.interface_reflections = interface_reflections;
  limits_.glossy_as_mirror = false;  // their lobes are sampled here
  emitter_of_.assign(scene.polygons.size(), -1);
  for (const EmittingFace& f : faces_from_polygons(scene)) {
    if (f.exitance == Rgb::Zero()) continue;
    int& index = emitter_of_[f.polygon];
    if (index < 0) {
      index = static_cast<int>(emitters_.size());
      emitters_.push_back({{}, {}, 0, f.normal, f.exitance});
    }
    Emitter& e = emitters_[index];
    for (size_t i = 1; i + 1 < f.vertices.size(); ++i) {
      const Vec3 &a = f.vertices[0], &b = f.vertices[i], &c = f.vertices[i + 1];
      e.triangles.push_back({a, b, c});
      e.area += 0.5 * (b - a).cross(c - a).norm();
      e.cumulative.push_back(e.area);
    }
  }
}

double PathTracer::cosine_weight(double cos_p, const Emitter& e, double r, double cos_z) {
  // Solid-angle densities: the cosine ray's cos_p / pi, the emitter sample's r^2 / (A cos_z).
  const double p_cosine = cos_p / std::numbers::pi;
  const double p_light = cos_z > 0 ? r * r / (e.area * cos_z) : INFINITY;
  return std::isfinite(p_light) ? p_cosine / (p_cosine + p_light) : 0.0;
}

Rgb PathTracer::straight_emission(const Vec3& p, const Vec3& normal, std::mt19937_64& rng) const {
  // Next-event estimation: per emitting polygon, one point z uniform on it (density 1 / A), and
  // M T(p, z) cos_p cos_z A / (pi r^2) estimates the light it sends straight to p, T what the
  // polygons between pass (0 through an opaque one); its back radiates nothing. Weighted by
  // the balance heuristic against the cosine rays (which count the rest of it).
  // Point lights: their direct light, I cos / r^2 through what lies between, and by their
  // images in the perfect mirrors (nothing a cosine ray can hit: a point has no area, and a
  // mirror's image of one neither).
  std::uniform_real_distribution<double> u(0, 1);
  Rgb h = lights_(p, normal);
  for (const Emitter& e : emitters_) {
    const double pick = u(rng) * e.area;
    const size_t k = std::min<size_t>(
        std::lower_bound(e.cumulative.begin(), e.cumulative.end(), pick) - e.cumulative.begin(),
        e.triangles.size() - 1);
    const auto& [a, b, c] = e.triangles[k];
    double s = u(rng), t = u(rng);
    if (s + t > 1) s = 1 - s, t = 1 - t;
    const Vec3 z = a + s * (b - a) + t * (c - a);
    const Vec3 to = z - p;
    const double r2 = to.squaredNorm();
    if (!(r2 > 0)) continue;
    const double r = std::sqrt(r2);
    const Vec3 w = to / r;
    const double cos_p = normal.dot(w), cos_z = -e.normal.dot(w);
    if (!(cos_p > 0 && cos_z > 0)) continue;
    // From off the surface and half an offset back, skipping what lies that near p (polygons
    // through p are edge-on, as for the exact gatherers) and stopping short of the emitter.
    const Vec3 origin = p + offset_ * normal - 0.5 * offset_ * w;
    const Vec3 leg = z - origin;
    const double distance = leg.norm();
    const Rgb passed = caster_.transmittance({origin, leg / distance}, 1.5 * offset_,
                                             distance * (1 - relative::kMatch) - offset_, offset_);
    if (passed == Rgb::Zero()) continue;
    const double weight = 1 - cosine_weight(cos_p, e, r, cos_z);
    h += (weight * e.area * cos_p * cos_z / (std::numbers::pi * r2)) *
         e.exitance.cwiseProduct(passed);
  }
  return h;
}

template <typename Incoming>
Rgb PathTracer::glossy_radiance(const Vec3& p, const Vec3& normal, const Vec3& shading,
                                const Vec3& out, const Material& m, std::mt19937_64& rng,
                                const Incoming& incoming) const {
  const double cos_out = normal.dot(out);
  if (cos_out == 0) return Rgb::Zero();
  const double sigma = m.gloss;
  // The point lights by next-event estimation: their highlight.
  const Rgb l = glossy_highlight(scene_, caster_, m, p, normal, shading, out, offset_);
  // The rest by one direction drawn from one lobe: reflection off a glossy mirror's front, or
  // transmission through a roughened pane (from either side), whichever applies, the other by
  // chance when both do (the estimate divided by its probability, 1/2).
  const bool can_reflect = m.is_glossy_mirror() && cos_out > 0;
  const bool can_pass = m.is_glossy_pane();
  if (!can_reflect && !can_pass) return l;
  std::uniform_real_distribution<double> pick(0, 1);
  const bool passes = can_pass && (!can_reflect || pick(rng) < 0.5);
  const double choice = can_reflect && can_pass ? 2.0 : 1.0;
  const Rgb weight = (passes ? m.glossy_transmittance : m.specular) * choice;
  const Vec3 lit_normal =
      passes ? Vec3(cos_out > 0 ? -normal : normal) : Vec3(cos_out > 0 ? normal : -normal);
  const Vec3 origin = p + offset_ * lit_normal;
  // The rest: a direction w drawn about the lobe's centre for `out` (-reflect(out): the angle
  // between out and the mirror direction of light from w is the angle between w and it), phi
  // as a 2D Gaussian of the angle, so its density per steradian is rho(phi) phi / sin(phi); the
  // estimate s rho cos_in L / (cos_out density) = s cos_in (sin phi / phi) L / cos_out.
  std::uniform_real_distribution<double> u(0, 1);
  const double phi = sigma * std::sqrt(-2 * std::log(1 - u(rng)));
  const double psi = 2 * std::numbers::pi * u(rng);
  if (phi >= std::numbers::pi) return l;
  const Vec3 centre = passes ? Vec3(-out) : Vec3(-reflect(out, shading));
  const PlaneFrame frame(Vec3::Zero(), centre);
  const Vec3 w =
      std::cos(phi) * centre + std::sin(phi) * (std::cos(psi) * frame.u + std::sin(psi) * frame.v);
  const double cos_in = lit_normal.dot(w);
  if (!(cos_in > 0)) return l;
  const double jacobian = phi > 0 ? std::sin(phi) / phi : 1.0;
  return l + weight.cwiseProduct(incoming(origin - 0.5 * offset_ * w, w)) *
                 (cos_in * jacobian / std::abs(cos_out));
}

PathTraceEstimate PathTracer::irradiance(const Vec3& x, const Vec3& n, int paths,
                                         uint64_t seed) const {
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + 7);
  std::uniform_real_distribution<double> u(0, 1);
  // pi times the radiance arriving along the ray (origin, d), as the sum over the surfaces it
  // meets (through filters, off mirrors, across interfaces) of what each sends back along it:
  // emission, diffuse reflection (one sample of H there, after `bounces` diffuse bounces) and
  // glossy reflection (003's lobe). With `shared`, the ray was cosine-sampled at a point whose
  // normal it is: emitters it meets straight share their light with that point's samples
  // (straight_emission) by their weights; otherwise they count whole.
  const auto incoming = [&](const auto& self, const Vec3& origin, const Vec3& d, int bounces,
                            const Vec3* shared) -> Rgb {
    Rgb radiance = Rgb::Zero();
    caster_.follow(
        {origin, d}, limits_, offset_,
        [&](const Hit& hit, const Rgb& weight, int reflections) {
          const Material& m = scene_.materials[scene_.polygons[hit.polygon].material];
          // Russian roulette past two bounces, by the largest reflectance.
          const auto keep_for = [&](const Rgb& r) {
            return bounces < 2 ? 1.0 : std::min(0.95, r.maxCoeff());
          };
          const auto glossy_part = [&] {
            const double keep = keep_for(m.specular.cwiseMax(m.glossy_transmittance));
            if (!(u(rng) < keep)) return Rgb(Rgb::Zero());
            const Vec3 shading = shading_normal(scene_.polygons[hit.polygon], hit.point);
            return Rgb(glossy_radiance(hit.point, hit.normal, shading, -hit.direction, m, rng,
                                       [&](const Vec3& o, const Vec3& w) {
                                         return self(self, o, w, bounces + 1, nullptr);
                                       }) /
                       keep);
          };
          if (!hit.front_facing) {  // only a roughened pane sends light out of its back
            if (m.is_glossy_pane()) radiance += weight.cwiseProduct(glossy_part());
            return;
          }
          Rgb b = m.emission;
          const int emitter = emitter_of_[hit.polygon];
          if (shared && reflections == 0 && emitter >= 0) {  // seen straight: shared
            const Emitter& e = emitters_[emitter];
            b *= cosine_weight(shared->dot(d), e, hit.distance, -e.normal.dot(d));
          }
          const double keep = keep_for(m.reflectance);
          if (m.reflectance.maxCoeff() > 0 && u(rng) < keep) {
            // One sample of H at the hit: its emitters by points on them, the rest by one
            // cosine-weighted ray (the two combined by their weights).
            // (In this order: the random numbers are drawn as they always were.)
            const Vec3& at = hit.normal;
            Rgb h = straight_emission(hit.point, at, rng);
            const Vec3 next = cosine_direction(at, rng);
            h +=
                self(self, hit.point + offset_ * at - 0.5 * offset_ * next, next, bounces + 1, &at);
            b += m.reflectance.cwiseProduct(h) / keep;
          }
          if (m.is_glossy()) b += glossy_part();
          radiance += weight.cwiseProduct(b);
        },
        offset_);
    return radiance;
  };
  // One sample of H at (x, n): its emitters by points on them, the rest by one cosine-weighted
  // ray. Off the surface along its normal, and half that back along the ray, so that no ray
  // starts inside a plane (at a point on an edge the lift along the normal stays in the
  // neighbour's); what lies that near the point is passed (RayCaster::follow), as the exact
  // gatherers see polygons through x edge-on.
  const auto sample = [&]() -> Rgb {
    Rgb h = straight_emission(x, n, rng);
    const Vec3 d = cosine_direction(n, rng);
    return h + incoming(incoming, x + offset_ * n - 0.5 * offset_ * d, d, 0, &n);
  };
  Rgb sum = Rgb::Zero(), sum2 = Rgb::Zero();
  for (int i = 0; i < paths; ++i) {
    const Rgb h = sample();
    sum += h;
    sum2 += h.cwiseProduct(h);
  }
  PathTraceEstimate e;
  const double count = std::max(paths, 1);
  e.mean = sum / count;
  if (paths > 1) {
    const Rgb variance =
        ((sum2 / count - e.mean.cwiseProduct(e.mean)) * (count / (count - 1))).cwiseMax(0);
    e.standard_error = (variance / count).cwiseSqrt();
  }
  return e;
}

}  // namespace rad
