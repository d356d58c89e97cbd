// Glossy backward polygon beams (paper 003 §4): the model against an independent adaptive
// cubature of the physics it models (tests/glossy_cubature.h), its specular limit against the
// exact mirror image of the light, its continuity across the flux triangle's edges and corners
// (§4.2.2's own requirement), and its degenerate cases.
#include "geometry/glossy_beam.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>

#include "tests/glossy_cubature.h"

namespace rad {
namespace {

/// A flat triangle at z = 1 facing down, lit from below, reflecting onto the floor z = 0.
GlossyTriangle ceiling_triangle(double scale = 1) {
  GlossyTriangle t;
  const Vec3 c(0.1, 0.0, 1);
  t.vertex = {c + scale * Vec3(-0.3, -0.2, 0), c + scale * Vec3(0.05, 0.3, 0),
              c + scale * Vec3(0.35, -0.25, 0)};
  const Vec3 n = (t.vertex[1] - t.vertex[0]).cross(t.vertex[2] - t.vertex[0]).normalized();
  t.normal = {n, n, n};
  return t;
}

const Vec3 kLight(-0.5, 0.2, 0.4);
const Vec3 kUp(0, 0, 1);

/// The beams of t split into n^2 similar triangles (midpoint subdivision, normals interpolated),
/// summed at f: a light at `light` of unit intensity, specular weight `weight`.
Rgb subdivided(const GlossyTriangle& t, int n, double sigma, const Vec3& f, const Vec3& normal,
               const Vec3& light = kLight, const Rgb& weight = Rgb::Ones()) {
  const auto& v = t.vertex;
  const auto at = [&](double i, double j) {
    const double a = i / n, b = j / n;
    return std::pair{(1 - a - b) * v[0] + a * v[1] + b * v[2],
                     ((1 - a - b) * t.normal[0] + a * t.normal[1] + b * t.normal[2]).normalized()};
  };
  Rgb sum = Rgb::Zero();
  const auto add = [&](std::pair<Vec3, Vec3> p, std::pair<Vec3, Vec3> q, std::pair<Vec3, Vec3> r) {
    GlossyTriangle piece;
    piece.vertex = {p.first, q.first, r.first};
    piece.normal = {p.second, q.second, r.second};
    piece.transmits = t.transmits;
    sum += GlossyBeam(light, Rgb::Ones(), piece, weight, sigma).irradiance(f, normal);
  };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; i + j < n; ++j) {
      add(at(i, j), at(i + 1, j), at(i, j + 1));
      if (i + j + 1 < n) add(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return sum;
}

/// Floor fragments in and around the beam's highlight, the lobe's centre at about (1, -0.1).
const Vec3 kFragments[] = {Vec3(0.6, -0.2, 0), Vec3(0.8, 0, 0), Vec3(1.0, -0.2, 0),
                           Vec3(1.3, 0.3, 0), Vec3(2.0, -1, 0)};

TEST(GlossyBeam, SolidAngleMeetsClosedForms) {
  // An octant's triangle from the origin: 4 pi / 8. A square of side 2a at height h over its
  // centre, as two triangles: 4 arcsin(a^2 / (a^2 + h^2)).
  EXPECT_NEAR(triangle_solid_angle(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()),
              std::numbers::pi / 2, 1e-14);
  const double a = 0.7, h = 1.3;
  const Vec3 p(0, 0, h), c0(-a, -a, 0), c1(a, -a, 0), c2(a, a, 0), c3(-a, a, 0);
  EXPECT_NEAR(triangle_solid_angle(p, c0, c1, c2) + triangle_solid_angle(p, c0, c2, c3),
              4 * std::asin(a * a / (a * a + h * h)), 1e-14);
  EXPECT_EQ(triangle_solid_angle(Vec3(0.2, 0.2, 0), c0, c1, c2), 0) << "in the plane";
}

TEST(GlossyBeam, SplitFineItConvergesNearThePhysicsItModels) {
  // The model is good when each scatterer subtends a small angle against sigma (003 §4.5: the
  // flat facets under the Gaussian): split into 64^2 pieces, the sum of their beams comes
  // within 13% of the cubature of the physics at every fragment, for sigma 0.05 to 0.2; the
  // rest is the angular mapping of §4.2.1 (angles laid out along flux-plane directions), which
  // splitting does not remove. One beam for the whole triangle is off by up to 30 times.
  const GlossyTriangle t = ceiling_triangle();
  double worst_whole = 0;
  for (const double sigma : {0.05, 0.1, 0.2}) {
    const GlossyBeam beam(kLight, Rgb::Ones(), t, Rgb::Ones(), sigma);
    for (const Vec3& f : kFragments) {
      const double physics = test::GlossyCubature(beam, f, kUp).integrate(1e-10);
      ASSERT_GT(physics, 1e-3);
      const double split = subdivided(t, 64, sigma, f, kUp)[0];
      EXPECT_NEAR(split / physics, 1, 0.13) << "sigma " << sigma << " at " << f.transpose();
      worst_whole = std::max(worst_whole, beam.irradiance(f, kUp)[0] / physics);
    }
  }
  EXPECT_GT(worst_whole, 10) << "the test must show what splitting buys";
}

TEST(GlossyBeam, SharpLobesTendToTheMirrorImageOfTheLight) {
  // sigma -> 0 on a flat triangle: the light's mirror image L' seen through the triangle gives
  // I s cos / |F - L'|^2 (the exact mirror of 000 §3 for a point light) where the line F L'
  // passes through the triangle, and nothing elsewhere.
  const GlossyTriangle t = ceiling_triangle();
  const Vec3 image(kLight.x(), kLight.y(), 2 - kLight.z());
  const Rgb weight(0.9, 0.6, 0.3);
  // Points inside its footprint (the vertices' images (0.3, -0.867), (1.233, 0.467),
  // (2.033, -1)), off the pieces' edges.
  for (const Vec3& f : {Vec3(1.19, -0.47, 0), Vec3(1.0, -0.5, 0), Vec3(1.5, -0.6, 0)}) {
    const Vec3 to = image - f;
    const Rgb mirror = weight * (to.z() / std::pow(to.norm(), 3));
    const Rgb sum = subdivided(t, 64, 1e-4, f, kUp, kLight, weight);
    EXPECT_LE((sum - mirror).cwiseAbs().maxCoeff(), 1e-2 * mirror.maxCoeff())
        << "at " << f.transpose() << ": " << sum.transpose() << " against " << mirror.transpose();
  }
  // Outside the specular beam a sharp lobe sends nothing.
  const GlossyBeam sharp(kLight, Rgb::Ones(), t, weight, 1e-4);
  EXPECT_EQ(sharp.irradiance(Vec3(2.5, 0.5, 0), kUp), Rgb::Zero());
}

/// The largest jump of E across the flux triangle's edges: along rays on the floor from a
/// point inside, the crossing found by bisection on `inside`, E compared at +- eps.
double largest_jump_at_edges(const GlossyBeam& beam, double eps) {
  const Vec3 inside_point(1.0, -0.1, 0);
  double worst = 0;
  for (int k = 0; k < 72; ++k) {
    const double a = 2 * std::numbers::pi * (k + 0.5) / 72;
    const Vec3 dir(std::cos(a), std::sin(a), 0);
    double lo = 0, hi = 5;
    if (beam.volume(inside_point + hi * dir).inside) continue;
    for (int i = 0; i < 100; ++i) {
      const double mid = 0.5 * (lo + hi);
      (beam.volume(inside_point + mid * dir).inside ? lo : hi) = mid;
    }
    const Vec3 edge = inside_point + lo * dir;
    const double in = beam.irradiance(edge - eps * dir, kUp)[0];
    const double out = beam.irradiance(edge + eps * dir, kUp)[0];
    worst = std::max(worst, std::abs(in - out) / std::max(in, out));
  }
  return worst;
}

/// The largest jump of E between neighbours spaced h apart on circles around the highlight
/// (crossing the boundaries between the edge and vertex regions of Fig. 12), relative.
double largest_step_around(const GlossyBeam& beam, double h) {
  double worst = 0;
  for (const double radius : {0.6, 0.9, 1.4}) {
    const int steps = static_cast<int>(2 * std::numbers::pi * radius / h);
    double previous = -1;
    for (int k = 0; k <= steps; ++k) {
      const double a = 2 * std::numbers::pi * k / steps;
      const double e =
          beam.irradiance(Vec3(1.0 + radius * std::cos(a), -0.1 + radius * std::sin(a), 0), kUp)[0];
      if (previous >= 0) worst = std::max(worst, std::abs(e - previous) / std::max(e, previous));
      previous = e;
    }
  }
  return worst;
}

TEST(GlossyBeam, ContinuousAcrossTheFluxTrianglesEdgesAndCorners) {
  // 003 §4.2.2: "no discontinuities between the volumes calculated for fragment positions
  // within and outside of the flux triangle". Across the edges, the jump falls with the gap
  // (1e-6 at 1e-9); around the highlight the steps between neighbours fall in proportion to
  // their spacing (a jump would not).
  for (const double sigma : {0.05, 0.2}) {
    const GlossyBeam beam(kLight, Rgb::Ones(), ceiling_triangle(), Rgb::Ones(), sigma);
    EXPECT_LT(largest_jump_at_edges(beam, 1e-9), 1e-6) << "sigma " << sigma;
    const double coarse = largest_step_around(beam, 1e-3), fine = largest_step_around(beam, 1e-4);
    EXPECT_LT(fine, 0.2 * coarse) << "sigma " << sigma << ": steps " << coarse << " then " << fine;
  }
}

TEST(GlossyBeam, DegenerateConfigurationsStayFiniteAndPhysical) {
  const GlossyTriangle t = ceiling_triangle();
  const GlossyBeam beam(kLight, Rgb::Ones(), t, Rgb::Ones(), 0.1);
  // O at a corner of ABC: F at a flux vertex (the floor point on vertex 0's ray).
  const Vec3 image(kLight.x(), kLight.y(), 2 - kLight.z());
  const Vec3 v0 = t.vertex[0];
  const Vec3 corner = v0 + (v0.z() / (image.z() - v0.z())) * (v0 - image);
  ASSERT_NEAR(corner.z(), 0, 1e-12);
  const double at_corner = beam.irradiance(corner, kUp)[0];
  EXPECT_TRUE(std::isfinite(at_corner) && at_corner > 0);
  EXPECT_NEAR(beam.irradiance(corner + Vec3(1e-9, 0, 0), kUp)[0], at_corner, 1e-6 * at_corner);
  // Tiny and huge sigma: finite, non-negative; the clamp keeps P_E <= 1 in E.
  for (const double sigma : {1e-8, 1e-3, 1.0, 3.0}) {
    const GlossyBeam b(kLight, Rgb::Ones(), t, Rgb::Ones(), sigma);
    for (const Vec3& f : kFragments) {
      const Rgb e = b.irradiance(f, kUp);
      EXPECT_TRUE(e.allFinite() && e.minCoeff() >= 0) << "sigma " << sigma;
    }
  }
  // The light in the scatterer's plane, or behind a reflector: no beam.
  EXPECT_TRUE(GlossyBeam(Vec3(3, 0, 1), Rgb::Ones(), t, Rgb::Ones(), 0.1).empty());
  EXPECT_TRUE(GlossyBeam(Vec3(0, 0, 2), Rgb::Ones(), t, Rgb::Ones(), 0.1).empty());
  // A fragment behind the scatterer (above the ceiling triangle), or facing away: nothing.
  EXPECT_EQ(beam.irradiance(Vec3(1, 0, 2), -kUp), Rgb::Zero());
  EXPECT_EQ(beam.irradiance(Vec3(1, -0.1, 0), -kUp), Rgb::Zero());
  EXPECT_EQ(test::GlossyCubature(beam, Vec3(1, 0, 2), -kUp).integrate(1e-12), 0);
}

TEST(GlossyBeam, AFocusingBeamStaysFiniteAtItsFocus) {
  // Vertex normals tilted to the bisectors of the light and a focus Q: the three rays meet at
  // Q, the flux triangle collapses there, and E takes the limit Phi_s cos rho(0) / d^2; near
  // Q the model stays within 0.9 to 1.4 times the physics (measured: 0.8% over it at Q and
  // 1e-7 from it; 0.01 from it, 2.08 times the physics without the clamp at the lobe's peak
  // density, 1.30 times with it).
  GlossyTriangle t = ceiling_triangle(0.3);
  const Vec3 focus(0.6, -0.1, 0);
  for (int k = 0; k < 3; ++k) {
    const Vec3& v = t.vertex[k];
    t.normal[k] = ((kLight - v).normalized() + (focus - v).normalized()).normalized();
  }
  const GlossyBeam beam(kLight, Rgb::Ones(), t, Rgb::Ones(), 0.05);
  for (const Vec3& f : {focus, Vec3(focus + Vec3(1e-7, 0, 0)), Vec3(focus + Vec3(0.01, 0.01, 0))}) {
    const double e = beam.irradiance(f, kUp)[0];
    const double physics = test::GlossyCubature(beam, f, kUp).integrate(1e-10);
    EXPECT_TRUE(std::isfinite(e) && e > 0) << "at " << f.transpose();
    EXPECT_GT(e, 0.9 * physics) << "at " << f.transpose();
    EXPECT_LT(e, 1.4 * physics) << "at " << f.transpose();
  }
}

TEST(GlossyBeam, ARoughenedPaneSendsItsLightOnThroughItAndConverges) {
  // Transmission (003 Fig. 13): the lobe is centred on the straight-through direction and the
  // light goes to the far side; split fine, it comes near the physics as reflection does.
  GlossyTriangle t = ceiling_triangle();
  t.transmits = true;
  const Vec3 above(0.2, 0.1, 1.8);  // a light above the pane lights the floor through it
  const GlossyBeam beam(above, Rgb::Ones(), t, Rgb::Ones(), 0.1);
  ASSERT_FALSE(beam.empty());
  EXPECT_EQ(beam.irradiance(Vec3(0, 0, 1.5), -kUp), Rgb::Zero()) << "the light's own side";
  for (const Vec3& f : {Vec3(0.0, -0.1, 0), Vec3(0.3, 0.2, 0), Vec3(0.8, -0.5, 0)}) {
    const double physics = test::GlossyCubature(beam, f, kUp).integrate(1e-10);
    ASSERT_GT(physics, 1e-4);
    const double split = subdivided(t, 48, 0.1, f, kUp, above)[0];
    EXPECT_NEAR(split / physics, 1, 0.13) << "at " << f.transpose();
  }
}

}  // namespace
}  // namespace rad
