#include "localpass/path_tracer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "scene/polygon.h"

namespace rad {
namespace {

/// A cosine-weighted direction about n (Malley's method).
Vec3 cosine_direction(const Vec3& n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const PlaneFrame frame(Vec3::Zero(), n);
  const double r2 = u(rng), phi = 2 * std::numbers::pi * u(rng);
  const double r = std::sqrt(r2);
  return r * std::cos(phi) * frame.u + r * std::sin(phi) * frame.v +
         std::sqrt(std::max(0.0, 1 - r2)) * n;
}

}  // namespace

PathTracer::PathTracer(const Scene& scene)
    : scene_(scene), caster_(scene), offset_(scene.tolerance().ray_offset) {}

PathTraceEstimate PathTracer::irradiance(const Vec3& x, const Vec3& n, int paths,
                                         uint64_t seed) const {
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + 7);
  std::uniform_real_distribution<double> u(0, 1);
  // One sample of H at (p, normal) after `bounces` diffuse bounces.
  const auto sample = [&](const auto& self, const Vec3& p, const Vec3& normal, int bounces) -> Rgb {
    Rgb h = Rgb::Zero();
    const Vec3 d = cosine_direction(normal, rng);
    // Off the surface along its normal, and half that back along the ray, so that no ray
    // starts inside a plane (at a point on an edge the lift along the normal stays in the
    // neighbour's); what lies that near the point is passed (RayCaster::follow), as the exact
    // gatherers see polygons through x edge-on.
    caster_.follow(
        {p + offset_ * normal - 0.5 * offset_ * d, d}, scene_.mirror_depth, offset_,
        [&](const Hit& hit, const Rgb& weight) {
          if (!hit.front_facing) return;
          const Material& m = scene_.materials[scene_.polygons[hit.polygon].material];
          Rgb b = m.emission;
          if (m.reflectance.maxCoeff() > 0) {
            const double keep = bounces < 2 ? 1.0 : std::min(0.95, m.reflectance.maxCoeff());
            if (u(rng) < keep) {
              b +=
                  m.reflectance.cwiseProduct(self(self, hit.point, hit.normal, bounces + 1)) / keep;
            }
          }
          h += weight.cwiseProduct(b);
        },
        offset_);
    return h;
  };
  Rgb sum = Rgb::Zero(), sum2 = Rgb::Zero();
  for (int i = 0; i < paths; ++i) {
    const Rgb h = sample(sample, x, n, 0);
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
