#include "localpass/cluster_bounds.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace rad {

KernelBounds kernel_bounds(const Cluster& cluster, const Vec3& x, const Vec3& n, double h) {
  constexpr double pi = std::numbers::pi;
  double up_min = std::numeric_limits<double>::infinity(), up_max = -up_min, r2_max = 0;
  for (const Vec3& v : cluster.outline) {
    const Vec3 w = v - x;
    const double up = n.dot(w);
    up_min = std::min(up_min, up), up_max = std::max(up_max, up);
    r2_max = std::max(r2_max, w.squaredNorm());
  }
  // In-plane reach: |u . d| <= |in-plane part of u| <= its largest value at a vertex.
  const double w_max = std::sqrt(std::max(0.0, r2_max - h * h));
  const double r2_min = std::max(h * h, cluster.box.squaredExteriorDistance(x));
  KernelBounds bounds;
  bounds.kmax = h * std::max(0.0, up_max) / (pi * r2_min * r2_min);
  bounds.kmin = std::min(h * std::max(0.0, up_min) / (pi * r2_max * r2_max), bounds.kmax);
  bounds.above_horizon = up_min >= 0;
  if (!bounds.above_horizon) return bounds;
  const Vec3 u = cluster.center - x;
  const double r2 = u.squaredNorm();
  bounds.gradient = h / pi * (n / (r2 * r2) - 4 * n.dot(u) / (r2 * r2 * r2) * u);
  // The second derivative along d (cluster_bounds.h), term by term at r >= r_min:
  // |2 (n . d)(4 (u . d) / r^6)| <= 8 n_in_plane min(w_max, r) / r^6, with n_in_plane the
  // length of n's part in the plane (d lies in it); |f (24 (u . d)^2 / r^8 - 4 / r^6)| <=
  // up_max max(24 min(w_max^2, r^2) / r^8, 4 / r^6). Each is largest at r = r_min.
  const double r6 = r2_min * r2_min * r2_min, r_min = std::sqrt(r2_min);
  const double n_in_plane = std::sqrt(std::max(0.0, 1 - std::pow(n.dot(cluster.normal), 2)));
  const double across = 8 * n_in_plane * std::min(w_max, r_min) / r6;
  const double along = std::max(0.0, up_max) *
                       std::max(24 * std::min(w_max * w_max, r2_min) / (r6 * r2_min), 4 / r6);
  bounds.remainder = 0.5 * h / pi * (across + along) * cluster.radius * cluster.radius;
  return bounds;
}

}  // namespace rad
