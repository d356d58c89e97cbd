#pragma once
/// Bounds on the point-to-area kernel over a cluster's outline, the pieces of the local pass's
/// certified intervals (localpass/local_pass.h proves how they combine).
///
/// The kernel from x (unit normal n) to a point y of a plane at height h > 0 below x is
///   k(y) = cos+(theta_x) cos(theta_y) / (pi r^2) = h max(0, n . u) / (pi r^4),  u = y - x,
/// since cos(theta_y) r = h on the plane: FF(x, A) = integral of k over A (paper 004 eq. 4).
#include <Eigen/Core>

#include "localpass/cluster_tree.h"

namespace rad {

struct KernelBounds {
  /// kmin <= k(y) <= kmax for every y of the outline.
  double kmin = 0, kmax = 0;
  /// The outline lies wholly above x's horizon (n . u >= 0 on it), so k is the smooth
  /// h (n . u) / (pi r^4) there and the Taylor expansion below holds.
  bool above_horizon = false;
  /// k(y) = k(center) + gradient . (y - center) + R(y) with |R(y)| <= remainder for every y
  /// of the outline (only when above_horizon; the center is the cluster's area centroid).
  Vec3 gradient = Vec3::Zero();
  double remainder = 0;
};

/// The kernel's range and first-order expansion over the cluster's outline, for x at height
/// h > 0 in front of its plane. Cost: one pass over the outline's vertices.
///
/// Range: the numerator h max(0, n . u) is linear in y (clamped), so it ranges between its
/// values at the vertices; r lies between max(h, distance from x to the outline's box) and the
/// largest vertex distance.
/// Expansion: along a segment from the center to y (inside the convex outline), with d the
/// unit direction (in the plane), f = n . u >= 0 (linear) and r >= rmin on it, the second
/// derivative of k = (h / pi) f r^-4 is
///   (h / pi) [2 (n . d)(-4 (u . d) / r^6) + f (24 (u . d)^2 / r^8 - 4 / r^6)].
/// |n . d| is at most the length of n's part in the plane, |u . d| at most min(r, w_max) with
/// w_max the largest in-plane distance from x's foot to a vertex, f at most its largest vertex
/// value; the bound M2 that follows (cluster_bounds.cpp) is largest at r = rmin. Taylor's
/// theorem with the Lagrange remainder then gives |R(y)| <= M2 |y - center|^2 / 2, and
/// |y - center| <= the cluster's radius.
KernelBounds kernel_bounds(const Cluster& cluster, const Vec3& x, const Vec3& n, double h);

}  // namespace rad
