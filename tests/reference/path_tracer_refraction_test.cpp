// The path tracer across refracting interfaces (000 §4), before it serves as the reference of
// the refraction heuristic: against closed forms for a uniform source seen through a flat slab
// and from inside a medium, each within 4 standard errors at a fixed seed. The expected values
// come from a 1D quadrature over the angle with Hecht's sine and tangent forms of Fresnel's
// equations, not from geometry/refraction.h.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "reference/path_tracer.h"
#include "tests/closed_forms.h"
#include "tests/path_trace_checks.h"
#include "tests/scene_builder.h"

namespace rad {
namespace {

using test::SceneBuilder;
constexpr double kPi = std::numbers::pi;

/// Simpson's rule on [a, b] with `intervals` (even) intervals.
double integrate(const std::function<double(double)>& f, double a, double b,
                 int intervals = 20000) {
  const double h = (b - a) / intervals;
  double sum = f(a) + f(b);
  for (int i = 1; i < intervals; ++i) sum += f(a + i * h) * (i % 2 ? 4 : 2);
  return sum * h / 3;
}

struct Slab {
  double ior = 1.5;
  bool fresnel = false;
  double transmittance = 1;  ///< per crossing, when !fresnel
  double attenuation = 0;
  double thickness = 1;
  int depth = 8;  ///< crossings and reflections followed along a path
};

/// H under a uniform source of exitance M = 1 filling the upper hemisphere, seen through the
/// slab: at outside angle i the light crosses twice and bounces 2j times inside, each pass
/// through the slab dimmed by exp(-attenuation thickness / cos t); the radiance ratios n^2 and
/// 1 / n^2 cancel. H = integral of that times 2 sin i cos i di.
double slab_closed_form(const Slab& s) {
  const int bounce_pairs = s.fresnel ? (s.depth - 2) / 2 : 0;
  return integrate(
      [&](double i) {
        const double t = std::asin(std::sin(i) / s.ior);
        const double r = s.fresnel ? test::hecht_reflectance(i, s.ior).unpolarised() : 0;
        const double pass = s.fresnel ? 1 - r : s.transmittance;
        const double dim = std::exp(-s.attenuation * s.thickness / std::cos(t));
        double through = 0;
        for (int j = 0; j <= bounce_pairs; ++j)
          through += pass * pass * std::pow(r, 2 * j) * std::pow(dim, 2 * j + 1);
        return through * 2 * std::sin(i) * std::cos(i);
      },
      0, kPi / 2);
}

/// The receiver at the origin facing up, the slab of `refraction` over it from z = 1 to
/// 1 + thickness (900 wide), the source 1000 wide at z = 3 + thickness facing down (M = 1).
Scene slab_scene(const Refraction& refraction, double thickness, int depth) {
  SceneBuilder b;
  b.rectangle(-1000, 1000, -1000, 1000, 3 + thickness, true,
              b.material("lamp", Rgb::Zero(), Rgb::Ones()));
  b.box({-900, -900, 1}, {900, 900, 1 + thickness}, b.material("glass", refraction));
  b.scene().refraction_depth = depth;
  return b.scene();
}

/// What a finite source misses of the uniform hemisphere: 1 - FF (Howell), a bound on the
/// closed form's error for a transmission <= 1 at every angle.
double finite_source_deficit(double height) {
  return 1 - test::howell_rectangle(-1000, 1000, -1000, 1000, height);
}

using test::within;

PathTraceEstimate trace_slab(const Refraction& r, const Slab& s, uint64_t seed) {
  const Scene scene = slab_scene(r, s.thickness, s.depth);
  return PathTracer(scene).irradiance(Vec3::Zero(), Vec3::UnitZ(), 20000, seed);
}

TEST(PathTracerRefraction, ClearSlabChangesNothing) {
  // Radiance / n^2 is kept across each interface: in at n^2 L, out at L. Without the n^2 the
  // slab would pass nothing different here (in and out cancel): the inside test below is the
  // one that tells.
  Refraction r;
  r.ior = Rgb::Constant(1.5);
  const double deficit = finite_source_deficit(4);
  EXPECT_TRUE(within(trace_slab(r, Slab{}, 1), Rgb::Ones(), 0.005, deficit));
}

TEST(PathTracerRefraction, IndexOneIsTwoFilters) {
  Refraction r;
  r.ior = Rgb::Ones();
  r.transmittance = Rgb(0.3, 0.6, 0.9);
  const Rgb expected = r.transmittance.cwiseProduct(r.transmittance);
  EXPECT_TRUE(
      within(trace_slab(r, Slab{1.0, false}, 2), expected, 0.005, finite_source_deficit(4)));
}

TEST(PathTracerRefraction, FresnelSlabWithInternalReflectionsAndDispersion) {
  // One index per channel (000 §4.3): each channel against its own closed form.
  Refraction r;
  r.ior = Rgb(1.3, 1.5, 1.8);
  r.fresnel = true;
  Rgb expected;
  for (int c = 0; c < 3; ++c) expected[c] = slab_closed_form(Slab{r.ior[c], true});
  EXPECT_LT(expected[2], expected[0]) << "a denser slab reflects more";
  EXPECT_TRUE(within(trace_slab(r, Slab{}, 3), expected, 0.005, finite_source_deficit(4)));
}

TEST(PathTracerRefraction, AttenuationAlongThePathInside) {
  Refraction r;
  r.ior = Rgb::Constant(1.5);
  r.attenuation = Rgb(0, 0.2, 1);
  Rgb expected;
  for (int c = 0; c < 3; ++c) {
    Slab s;
    s.attenuation = r.attenuation[c];
    expected[c] = slab_closed_form(s);
  }
  EXPECT_NEAR(expected[0], 1, 1e-9);
  EXPECT_TRUE(within(trace_slab(r, Slab{}, 4), expected, 0.005, finite_source_deficit(4)));
}

TEST(PathTracerRefraction, InsideTheMediumTheIrradianceIsTheSame) {
  // A receiver inside a medium of index n under a uniform source through a flat interface: the
  // radiance is n^2 L within the critical cone (sin = 1 / n) and nothing outside it (those
  // directions end in total internal reflection), so H = n^2 L pi / n^2 = M. Without the
  // radiance factor it would be M / n^2.
  SceneBuilder b;
  b.rectangle(-1000, 1000, -1000, 1000, 3, true, b.material("lamp", Rgb::Zero(), Rgb::Ones()));
  Refraction r;
  r.ior = Rgb(1.33, 1.5, 2.0);
  b.box({-900, -900, -1}, {900, 900, 1}, b.material("water", r));
  b.scene().refraction_depth = 8;
  // Each path finds n^2 or 0: a binary spread, 100,000 paths for 1% precision.
  const PathTraceEstimate e =
      PathTracer(b.scene()).irradiance(Vec3::Zero(), Vec3::UnitZ(), 100000, 5);
  EXPECT_TRUE(within(e, Rgb::Ones(), 0.01, finite_source_deficit(3)))
      << "M / n^2 would be " << (1 / r.ior.array().square());
}

}  // namespace
}  // namespace rad
