#pragma once
/// Glossy backward polygon beams (paper 003 §4): the light of a point light reflected (or
/// passed) by one glossy triangle, at a diffuse fragment. A heuristic: the paper's model,
/// implemented as printed where it is unambiguous; the choices where it is not are marked
/// "Choice" below and in docs/algorithms.md.
///
/// The model. The light (intensity I) sends the flux Phi_s = I Omega s into the beam (003
/// §4.1, Omega the triangle's solid angle from the light, s the specular weight). Each vertex
/// scatters its ray about its own normal (vertex normals: a smooth mesh's beams are warped by
/// them, §3). At a fragment F, the flux plane is the plane through F perpendicular to the mean
/// of the three scattered directions (the average wavefront normal); the rays meet it at the
/// flux triangle A_F B_F C_F of area A_perp (Fig. 5). Eq. 1 is the specular beam's irradiance,
/// Phi_s / A_perp cos(theta); eq. 3 weights it by the volume under the lobe rho over the domain
/// of scatter angles the triangle covers, which §4.2.1 maps to the triangle ABC with
/// A = phi_a l_a, ...: phi_a the angle between the ray from A_W to F and A_W's scattered
/// direction, l_a the unit direction from F to A_F in the flux plane (so O, the lobe's centre,
/// is F). §4.2.2 approximates the volume by flat facets over ABC (eq. 5):
///  - F inside the flux triangle (Fig. 11): facets AOB, BOC, COA, each its area times the mean
///    of rho at its corners (rho(0) at O);
///  - F outside (Fig. 12): split ABC at D, the point of the edge nearest the peak, into two
///    facets, D carrying rho at its own scatter angle; or, when a vertex is nearest, one facet
///    ABC.
/// E = Phi_s / A_perp cos(theta) min(P_E, 1).
///
/// Choices where the paper is silent or self-contradictory:
///  - Fig. 12's formula names the facet CAD twice ("||COA + AOD|| P_CAD + ||BOC + DOB|| P_CAD");
///    the two facets of the split are CAD and CDB (as §4.2.2 says: the edge is split at D), so
///    P_E = area(CAD) mean(rho_C, rho_A, rho_D) + area(CDB) mean(rho_C, rho_D, rho_B), with the
///    true areas of those triangles in the angular domain.
///  - Which edge, and where: D_F is the point of the flux triangle nearest F. On an edge's
///    interior, that edge is split there; at a vertex, no split (Fig. 12 step 4: "when A, B or
///    C is closer to the fragment than a split point D would be"). The nearest point moves
///    continuously with F, so the volume does too across the boundaries of these regions.
///  - D_W, the point of the scatterer's edge whose ray makes D: the paper reuses D_F's edge
///    parameter s; here s is the one whose scattered ray meets the flux plane at D_F (found by
///    bisection; the two agree for a parallel beam). Then at F on the flux triangle's edge,
///    phi_d = 0 and D = O, and the volume outside meets the volume inside: the continuity
///    §4.2.2 asks for. With the paper's s, phi_d there is the small angle between two rays of a
///    diverging beam, and the volume jumps.
///  - A collapsed flux triangle (a focus, A_perp -> 0): the angular triangle collapses with it
///    (the angles are ~ |V_F - F| / distance), and E tends to Phi_s cos(theta) rho(0) / d^2, d
///    the distance from F to the triangle; that limit is used when A_perp < 1e-12 d^2.
///  - A second clamp beside the paper's P_E <= 1: the density never passes the lobe's peak
///    over the squared height h of F above the triangle's plane, E <= Phi_s cos rho(0) / h^2,
///    which bounds the physics (no point of the triangle is nearer than h, and rho <= rho(0));
///    near a focus the facets pass it (measured 0.01 from the focus of a triangle 0.3 across:
///    2.08 times the physics without this clamp, 1.30 with it).
///  - theta, "the incoming radiance angle" of eq. 1: from F's normal to the direction from F
///    to the triangle's centroid, where the light comes from; inside a specular beam this is
///    the beam's mean direction, outside it is not (measured, split fine, sigma 0.2: with the
///    mean direction a fragment 1 away from the highlight gets 32% too much, with the
///    centroid's 4% too little).
///  - A fragment is lit only on the side the light leaves to: in front of a reflecting
///    triangle (on the light's side), behind a transmitting one (§3: "only scattering from the
///    front side"); and only where every scattered ray runs toward the flux plane (N . d > 0).
#include <array>

#include "geometry/vec.h"

namespace rad {

/// The normalised 2D Gaussian lobe of 003 §4.2 over the scatter angle phi (radians), per
/// steradian: rho(phi) = exp(-phi^2 / (2 sigma^2)) / (2 pi sigma^2).
double gaussian_lobe(double phi, double sigma);

/// The solid angle of triangle (a, b, c) seen from p (Van Oosterom and Strackee 1983), >= 0.
double triangle_solid_angle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// One scattering triangle: vertices counter-clockwise seen from the front, unit vertex normals
/// (all the face's normal for a flat triangle).
struct GlossyTriangle {
  std::array<Vec3, 3> vertex;
  std::array<Vec3, 3> normal;
  /// A roughened pane (transmittance with gloss): the lobe's centre is the incident direction,
  /// straight through; otherwise the mirror direction about the (interpolated) normal.
  bool transmits = false;
};

class GlossyBeam {
 public:
  /// The beam of a point light at `light` of intensity I through triangle t, specular weight
  /// `weight` (per channel), lobe spread sigma > 0 (radians).
  GlossyBeam(const Vec3& light, const Rgb& intensity, const GlossyTriangle& t, const Rgb& weight,
             double sigma);

  /// No light enters the beam: the light behind a reflecting triangle or in its plane.
  bool empty() const { return empty_; }
  /// Phi_s = I Omega s, per channel [W].
  const Rgb& flux() const { return flux_; }
  /// The irradiance at fragment f with unit normal n.
  Rgb irradiance(const Vec3& f, const Vec3& n) const;
  /// P_E before the clamp at f (the volume under the lobe over the angular domain), and the
  /// flux triangle's area there; for tests. Zero where the beam does not reach f.
  struct Volume {
    double p_e = 0;
    double flux_area = 0;
    bool inside = false;  ///< f lies in the flux triangle
  };
  Volume volume(const Vec3& f) const;

  /// The lobe's centre direction for light arriving at point p of the triangle with
  /// barycentric weights w (the normal interpolated and normalised).
  Vec3 scattered(const Vec3& p, const std::array<double, 3>& w) const;
  /// The unit mean of the vertices' scattered directions (the flux planes' normal).
  const Vec3& mean_direction() const { return mean_direction_; }
  const GlossyTriangle& triangle() const { return triangle_; }
  double sigma() const { return sigma_; }
  const Vec3& light() const { return light_; }

 private:
  /// Whether f is on the side the beam leaves to.
  bool on_lit_side(const Vec3& f) const;

  Vec3 light_;
  GlossyTriangle triangle_;
  Vec3 face_normal_;
  double sigma_;
  Rgb flux_ = Rgb::Zero();
  std::array<Vec3, 3> direction_;  ///< Scattered unit direction at each vertex
  Vec3 mean_direction_;            ///< Unit mean of the three: the flux planes' normal
  bool empty_ = true;
};

}  // namespace rad
