#pragma once
/// An unbiased path tracer of the scene itself (no solution): the independent reference the
/// whole pipeline is measured against, as Radiance was for the opaque Cornell box. Every bounce
/// is sampled. From x, a cosine-weighted direction is followed through filters and off mirrors
/// (RayCaster::follow: both are deterministic splits, weighted by transmittance and specular
/// reflectance); at each front-facing surface y met, the estimate gains E(y) + rho(y) H(y), and
/// H(y) is estimated the same way from one new cosine-weighted direction at y; across refracting
/// interfaces it is split into the refracted and the reflected ray, each followed exactly
/// (Snell, Fresnel, total internal reflection, attenuation inside: RayCaster::follow). Since
/// H = integral of (B / pi) cos theta dw, one cosine-weighted sample of B estimates H without a
/// weight. The emitters seen along straight lines (through filters) are also sampled directly,
/// a point on each emitting polygon with a shadow ray (next-event estimation: the small lamp of
/// a Cornell box is found by few cosine rays), and the two estimates of that light are combined
/// by multiple importance sampling (Veach's balance heuristic), which keeps each unbiased and
/// tames both the small lamp and the emitters next to the point; emission met after a mirror or
/// an interface is counted by the cosine rays alone (a refracting polygon is opaque to the
/// straight shadow rays). Russian roulette after the second bounce
/// keeps a path with probability q = min(0.95, max_c rho) and divides by q. Every part is an
/// unbiased estimate of its term, so the sum is.
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "scene/point_lights.h"
#include "scene/ray_caster.h"
#include "scene/scene.h"

namespace rad {

struct PathTraceEstimate {
  Rgb mean = Rgb::Zero();            ///< H(x) [W/m^2]
  Rgb standard_error = Rgb::Zero();  ///< Of the mean, from the spread of the paths
};

class PathTracer {
 public:
  /// The scene must outlive the tracer. `interface_reflections` false drops the light that
  /// refracting interfaces reflect (Fresnel, total internal reflection), as the heuristic of
  /// 000 §4 does: the reference of that model, where true is the reference of the physics.
  explicit PathTracer(const Scene& scene, bool interface_reflections = true);

  /// H(x) at unit normal n from `paths` paths, seeded by `seed` (e.g. the point's index): the
  /// same seed gives the same estimate on any thread. Thread-safe.
  PathTraceEstimate irradiance(const Vec3& x, const Vec3& n, int paths, uint64_t seed) const;

 private:
  /// An emitting polygon as triangles, sampled uniformly by area.
  struct Emitter {
    std::vector<std::array<Vec3, 3>> triangles;
    std::vector<double> cumulative;  ///< Areas summed up to each triangle
    double area = 0;
    Vec3 normal;
    Rgb exitance;
  };
  Rgb straight_emission(const Vec3& p, const Vec3& normal, std::mt19937_64& rng) const;
  /// pi times the radiance a glossy surface (the model of 003: s rho(angle between out and the
  /// mirror direction of in about the shading normal) per steradian, scattering the flux it
  /// receives) sends from p (unit normal `normal`, shading normal `shading`) in unit direction
  /// `out`: the point lights' by next-event
  /// estimation, the rest by one direction drawn from the lobe and `incoming` (pi times the
  /// radiance arriving along a ray, emitters counted whole).
  template <typename Incoming>
  Rgb glossy_radiance(const Vec3& p, const Vec3& normal, const Vec3& shading, const Vec3& out,
                      const Material& m, std::mt19937_64& rng, const Incoming& incoming) const;
  /// The balance-heuristic weight of a cosine-sampled ray from a point with normal n that
  /// meets emitter e at distance r, cos_z from its normal.
  static double cosine_weight(double cos_p, const Emitter& e, double r, double cos_z);

  const Scene& scene_;
  RayCaster caster_;
  double offset_ = 0;            ///< Rays start this far along the normal, off the surface
  RayCaster::Bends limits_;      ///< The scene's, and whether interfaces reflect
  PointLightIrradiance lights_;  ///< Straight and by the mirrors' images: no ray hits a light
  std::vector<Emitter> emitters_;
  std::vector<int> emitter_of_;  ///< Per polygon: its index in emitters_, or -1
};

}  // namespace rad
