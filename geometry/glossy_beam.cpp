#include "geometry/glossy_beam.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/planar.h"
#include "geometry/refraction.h"
#include "geometry/tolerance.h"

namespace rad {
namespace {

/// Area of the 2D triangle (a, b, c).
double area_2d(const Vec2& a, const Vec2& b, const Vec2& c) {
  return 0.5 * std::abs(cross_2d(b - a, c - a));
}

/// The parameter in [0, 1] of the point of segment [a, b] nearest the origin.
double nearest_on_segment(const Vec2& a, const Vec2& b) {
  const Vec2 e = b - a;
  const double length2 = e.squaredNorm();
  return length2 > 0 ? std::clamp(-a.dot(e) / length2, 0.0, 1.0) : 0.0;
}

}  // namespace

double gaussian_lobe(double phi, double sigma) {
  return std::exp(-phi * phi / (2 * sigma * sigma)) / (2 * std::numbers::pi * sigma * sigma);
}

double triangle_solid_angle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ra = a - p, rb = b - p, rc = c - p;
  const double la = ra.norm(), lb = rb.norm(), lc = rc.norm();
  const double numerator = std::abs(ra.dot(rb.cross(rc)));
  const double denominator = la * lb * lc + ra.dot(rb) * lc + ra.dot(rc) * lb + rb.dot(rc) * la;
  return 2 * std::atan2(numerator, denominator);
}

GlossyBeam::GlossyBeam(const Vec3& light, const Rgb& intensity, const GlossyTriangle& t,
                       const Rgb& weight, double sigma)
    : light_(light), triangle_(t), sigma_(sigma) {
  const auto& v = t.vertex;
  face_normal_ = (v[1] - v[0]).cross(v[2] - v[0]).normalized();
  const double height = face_normal_.dot(light - v[0]);
  // 003 §3: only the front scatters a reflection; a pane passes light from either side.
  if (!(t.transmits ? height != 0 : height > 0)) return;
  const double omega = triangle_solid_angle(light, v[0], v[1], v[2]);
  if (!(omega > 0)) return;
  flux_ = intensity.cwiseProduct(weight) * omega;
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    std::array<double, 3> w{0, 0, 0};
    w[k] = 1;
    direction_[k] = scattered(v[k], w);
    sum += direction_[k];
  }
  if (!(sum.norm() > 0)) return;
  mean_direction_ = sum.normalized();
  empty_ = false;
}

Vec3 GlossyBeam::scattered(const Vec3& p, const std::array<double, 3>& w) const {
  const Vec3 incident = (p - light_).normalized();
  if (triangle_.transmits) return incident;
  const Vec3 n =
      (w[0] * triangle_.normal[0] + w[1] * triangle_.normal[1] + w[2] * triangle_.normal[2])
          .normalized();
  return reflect(incident, n);
}

bool GlossyBeam::on_lit_side(const Vec3& f) const {
  const double light_side = face_normal_.dot(light_ - triangle_.vertex[0]);
  const double f_side = face_normal_.dot(f - triangle_.vertex[0]);
  // Reflected light stays on the light's side; transmitted light crosses to the other.
  return triangle_.transmits ? f_side * light_side < 0 : f_side * light_side > 0;
}

GlossyBeam::Volume GlossyBeam::volume(const Vec3& f) const {
  Volume out;
  if (empty_ || !on_lit_side(f)) return out;
  const Vec3& nf = mean_direction_;
  const auto& vw = triangle_.vertex;
  // The flux triangle: each vertex's scattered ray met by the flux plane through f (Fig. 5).
  std::array<Vec3, 3> vf;
  for (int k = 0; k < 3; ++k) {
    const double toward = nf.dot(direction_[k]);
    if (!(toward > 0)) return out;  // this ray never meets the flux plane ahead
    vf[k] = vw[k] + (nf.dot(f - vw[k]) / toward) * direction_[k];
  }
  out.flux_area = 0.5 * (vf[1] - vf[0]).cross(vf[2] - vf[0]).norm();
  // The flux plane in 2D, F at the origin.
  const Vec3 u = (std::abs(nf.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(nf).normalized();
  const Vec3 w = nf.cross(u);
  const auto to_2d = [&](const Vec3& p) { return Vec2(u.dot(p - f), w.dot(p - f)); };
  const std::array<Vec2, 3> flux{to_2d(vf[0]), to_2d(vf[1]), to_2d(vf[2])};
  // The angular domain (§4.2.1): vertex k at phi_k along the direction from F to its flux
  // vertex; rho at each.
  std::array<Vec2, 3> angular;
  std::array<double, 3> rho;
  const auto angular_point = [&](const Vec3& from, const Vec3& direction, const Vec2& at,
                                 double* rho_out) {
    const double phi = angle_between(f - from, direction);
    *rho_out = gaussian_lobe(phi, sigma_);
    const double length = at.norm();
    return length > 0 ? Vec2(phi * at / length) : Vec2(Vec2::Zero());
  };
  for (int k = 0; k < 3; ++k) angular[k] = angular_point(vw[k], direction_[k], flux[k], &rho[k]);
  const double rho_o = gaussian_lobe(0, sigma_);

  // Inside the flux triangle: the origin on the same side of all three edges.
  double sides[3];
  for (int k = 0; k < 3; ++k) sides[k] = cross_2d(flux[(k + 1) % 3] - flux[k], -flux[k]);
  const bool ccw = cross_2d(flux[1] - flux[0], flux[2] - flux[0]) >= 0;
  out.inside = ccw ? (sides[0] >= 0 && sides[1] >= 0 && sides[2] >= 0)
                   : (sides[0] <= 0 && sides[1] <= 0 && sides[2] <= 0);
  if (out.inside) {  // Fig. 11: AOB, BOC, COA
    for (int k = 0; k < 3; ++k) {
      const int j = (k + 1) % 3;
      out.p_e += 0.5 * std::abs(cross_2d(angular[k], angular[j])) * (rho[k] + rho_o + rho[j]) / 3;
    }
    return out;
  }
  // Outside (Fig. 12): the point of the flux triangle nearest F.
  int edge = 0;
  double t = 0, nearest = INFINITY;
  for (int k = 0; k < 3; ++k) {
    const Vec2 &a = flux[k], &b = flux[(k + 1) % 3];
    const double s = nearest_on_segment(a, b);
    const double d = (a + s * (b - a)).norm();
    if (d < nearest) nearest = d, edge = k, t = s;
  }
  const double whole = area_2d(angular[0], angular[1], angular[2]) * (rho[0] + rho[1] + rho[2]) / 3;
  if (!(t > 0 && t < 1)) {  // a vertex is nearest: no split (step 4)
    out.p_e = whole;
    return out;
  }
  const int x = edge, y = (edge + 1) % 3, z = (edge + 2) % 3;
  const Vec3 d_f = vf[x] + t * (vf[y] - vf[x]);
  // D_W: the point of the scatterer's edge whose scattered ray meets the flux plane at D_F
  // (bisection on the edge parameter; the hit's parameter along the flux edge rises from 0 at
  // X to 1 at Y).
  const Vec3 edge_f = vf[y] - vf[x];
  double lo = 0, hi = 1;
  Vec3 d_w = vw[x], d_dir = direction_[x];
  for (int i = 0; i < 60 && hi - lo > 1e-15; ++i) {
    const double s = 0.5 * (lo + hi);
    std::array<double, 3> weights{0, 0, 0};
    weights[x] = 1 - s, weights[y] = s;
    d_w = vw[x] + s * (vw[y] - vw[x]);
    d_dir = scattered(d_w, weights);
    const double toward = nf.dot(d_dir);
    if (!(toward > 0)) break;
    const Vec3 hit = d_w + (nf.dot(f - d_w) / toward) * d_dir;
    const double along = (hit - vf[x]).dot(edge_f) / edge_f.squaredNorm();
    (along < t ? lo : hi) = s;
  }
  double rho_d = 0;
  const Vec2 d = angular_point(d_w, d_dir, to_2d(d_f), &rho_d);
  out.p_e = area_2d(angular[z], angular[x], d) * (rho[z] + rho[x] + rho_d) / 3 +
            area_2d(angular[z], d, angular[y]) * (rho[z] + rho_d + rho[y]) / 3;
  return out;
}

Rgb GlossyBeam::irradiance(const Vec3& f, const Vec3& n) const {
  if (empty_) return Rgb::Zero();
  const Vec3 centroid = (triangle_.vertex[0] + triangle_.vertex[1] + triangle_.vertex[2]) / 3;
  const double d2 = (f - centroid).squaredNorm();
  const double cos_theta = n.dot(centroid - f) / std::sqrt(d2);
  if (!(cos_theta > 0)) return Rgb::Zero();
  const Volume v = volume(f);
  if (!(v.p_e > 0)) return Rgb::Zero();
  // A collapsed flux triangle (a focus): the limit rho(0) / d^2 of P_E / A_perp. Never more
  // than the lobe's peak density over the squared height above the triangle's plane (a bound
  // of the physics, which the facets pass near a focus).
  const double peak = gaussian_lobe(0, sigma_);
  const double density =
      v.flux_area < relative::kRounding * d2 ? peak / d2 : std::min(v.p_e, 1.0) / v.flux_area;
  const double height = face_normal_.dot(f - triangle_.vertex[0]);
  return flux_ * (cos_theta * std::min(density, peak / (height * height)));
}

}  // namespace rad
