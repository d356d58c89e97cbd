#pragma once
/// The optics of a flat interface between two media (paper 000 §4): Snell's law, the apparent
/// depth contraction the paper builds its heuristic on, and Fresnel's transmission. Indices are
/// relative: eta = n_far / n_near, n_near the index on the side the light is seen from (the
/// receiver's), n_far the index behind the interface (the source's side).
#include <optional>

#include "geometry/vec.h"

namespace rad {

/// Snell's law (000 eq. 6, n_near sin(theta_near) = n_far sin(theta_far)) for a ray of unit
/// direction `d` crossing a plane of unit normal `normal` (either orientation) from the near
/// medium into the far one, eta = n_far / n_near: the unit direction it continues in, in the
/// plane of d and the normal. Nothing at total internal reflection (sin(theta_far) would pass
/// 1). A ray along the plane (cos = 0) goes on at the critical angle when eta > 1 (to the side
/// `normal` does not point to), unchanged when eta = 1, and is totally reflected when eta < 1.
std::optional<Vec3> refract(const Vec3& d, const Vec3& normal, double eta);

/// The mirror image of unit direction `d` in a plane of unit normal `normal`.
inline Vec3 reflect(const Vec3& d, const Vec3& normal) { return d - 2 * normal.dot(d) * normal; }

/// 000 eqs. 7-8: what lies at depth t behind the interface, seen from the near side at
/// incidence cos_near (the cosine between the line of sight and the normal, in (0, 1]), appears
/// at depth k t, k = cos_near / sqrt(eta^2 - 1 + cos_near^2) (< 1 into a denser medium: the
/// bottom of a pool looks shallow; > 1 out of one). Nothing when eta^2 - 1 + cos_near^2 <= 0:
/// total internal reflection, no light comes through at that angle. Exact for a point on the
/// refracted ray of the line of sight (the ray's lateral offset is kept), which is the
/// heuristic of 000 §4.2: one angle per facet.
std::optional<double> depth_ratio(double cos_near, double eta);

/// 000 eq. 9: the affine map that moves every point q behind a facet toward the facet's plane
/// along its normal, q' = q + ((c - q) . n)(1 - k) n: depths scaled by k, the plane fixed.
struct DepthContraction {
  Vec3 point;   ///< c, a point of the facet's plane (000: its centroid)
  Vec3 normal;  ///< n, unit
  double k = 1;
  Vec3 operator()(const Vec3& q) const { return q + ((point - q).dot(normal) * (1 - k)) * normal; }
  /// The same map as q' = linear q + translation.
  Eigen::Matrix3d linear() const {
    return Eigen::Matrix3d::Identity() - (1 - k) * normal * normal.transpose();
  }
  Vec3 translation() const { return ((1 - k) * point.dot(normal)) * normal; }
};

/// The fraction of unpolarised light a smooth interface transmits (1 - the mean of the s and p
/// Fresnel reflectances) for light arriving at cos_near in (0, 1] from the near side, eta =
/// n_far / n_near; 0 at and beyond the critical angle. The same for the reversed path (the
/// Stokes relations), so the near side may be either end.
double fresnel_transmission(double cos_near, double eta);

}  // namespace rad
