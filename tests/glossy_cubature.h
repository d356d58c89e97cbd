#pragma once
/// The physics the glossy beams of paper 003 model, integrated independently of them: the
/// irradiance at a fragment F (unit normal n) from a point light (position L, intensity I)
/// scattered by a glossy triangle with the normalised Gaussian lobe rho about the centre
/// direction r(P) at each point P:
///   E(F) = s integral over the triangle of I cos_i(P) / |P - L|^2 rho(angle(F - P, r(P)))
///          max(0, n . (P - F) / |P - F|) / |F - P|^2 dA(P),
/// (the flux I cos_i dA / |P - L|^2 through dA, scattered per steradian by rho, received at F
/// by the inverse-square cosine law), with F lit only on the side the beam leaves to. Adaptive
/// cubature: Dunavant's degree-5 rule on a triangle against the sum over its four midpoint
/// children, split until they agree within the tolerance's share.
#include <array>
#include <cmath>

#include "geometry/glossy_beam.h"

namespace rad::test {

class GlossyCubature {
 public:
  /// The integrand's scalar part (per unit I s) at barycentric weights w of `beam`'s triangle.
  GlossyCubature(const GlossyBeam& beam, const Vec3& f, const Vec3& n)
      : beam_(beam), f_(f), n_(n) {}

  /// E / (I s), to about `tolerance` absolute.
  double integrate(double tolerance) const {
    const auto& v = beam_.triangle().vertex;
    const Vec3 normal = (v[1] - v[0]).cross(v[2] - v[0]).normalized();
    const double light_side = normal.dot(beam_.light() - v[0]);
    const double f_side = normal.dot(f_ - v[0]);
    if (beam_.triangle().transmits ? !(f_side * light_side < 0) : !(f_side * light_side > 0))
      return 0;
    const std::array<Vec3, 3> whole{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    return adapt(whole, rule(whole), tolerance, 0);
  }

 private:
  /// At barycentric weights b.
  double integrand(const Vec3& b) const {
    const auto& v = beam_.triangle().vertex;
    const Vec3 p = b[0] * v[0] + b[1] * v[1] + b[2] * v[2];
    const Vec3 normal = (v[1] - v[0]).cross(v[2] - v[0]).normalized();
    const Vec3 to_light = beam_.light() - p;
    const double cos_i = std::abs(normal.dot(to_light)) / to_light.norm();
    const Vec3 centre = beam_.scattered(p, {b[0], b[1], b[2]});
    const Vec3 to_f = f_ - p;
    const double phi = std::atan2(to_f.cross(centre).norm(), to_f.dot(centre));
    const double cos_f = std::max(0.0, -n_.dot(to_f) / to_f.norm());
    return cos_i / to_light.squaredNorm() * gaussian_lobe(phi, beam_.sigma()) * cos_f /
           to_f.squaredNorm();
  }
  double area(const std::array<Vec3, 3>& t) const {
    const auto& v = beam_.triangle().vertex;
    const auto point = [&](const Vec3& b) { return b[0] * v[0] + b[1] * v[1] + b[2] * v[2]; };
    return 0.5 * (point(t[1]) - point(t[0])).cross(point(t[2]) - point(t[0])).norm();
  }
  /// Dunavant's 7-point rule of degree 5 on the sub-triangle t (barycentric corners).
  double rule(const std::array<Vec3, 3>& t) const {
    static const double points[7][4] = {
        {1.0 / 3, 1.0 / 3, 1.0 / 3, 0.225},
        {0.059715871789770, 0.470142064105115, 0.470142064105115, 0.132394152788506},
        {0.470142064105115, 0.059715871789770, 0.470142064105115, 0.132394152788506},
        {0.470142064105115, 0.470142064105115, 0.059715871789770, 0.132394152788506},
        {0.797426985353087, 0.101286507323456, 0.101286507323456, 0.125939180544827},
        {0.101286507323456, 0.797426985353087, 0.101286507323456, 0.125939180544827},
        {0.101286507323456, 0.101286507323456, 0.797426985353087, 0.125939180544827}};
    double sum = 0;
    for (const auto& q : points) sum += q[3] * integrand(q[0] * t[0] + q[1] * t[1] + q[2] * t[2]);
    return sum * area(t);
  }
  double adapt(const std::array<Vec3, 3>& t, double coarse, double tolerance, int depth) const {
    const Vec3 ab = 0.5 * (t[0] + t[1]), bc = 0.5 * (t[1] + t[2]), ca = 0.5 * (t[2] + t[0]);
    const std::array<std::array<Vec3, 3>, 4> children{
        {{t[0], ab, ca}, {ab, t[1], bc}, {ca, bc, t[2]}, {ab, bc, ca}}};
    double values[4], fine = 0;
    for (int k = 0; k < 4; ++k) fine += values[k] = rule(children[k]);
    if (std::abs(fine - coarse) <= tolerance || depth >= 12) return fine;
    double sum = 0;
    for (int k = 0; k < 4; ++k) sum += adapt(children[k], values[k], tolerance / 2, depth + 1);
    return sum;
  }

  const GlossyBeam& beam_;
  Vec3 f_, n_;
};

}  // namespace rad::test
