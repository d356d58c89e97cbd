#pragma once
/// Certified interpolation over a tile: neighbouring points of one plane share the light that
/// reaches all of them smoothly, gathered at the tile's four corners and interpolated, with a
/// bound on the interpolation's error; the rest is gathered at each point on its own.
///
/// The split. Over the box R around the tile's points and corners, a cluster c is *smooth*
/// when every x of R is strictly in front of c's plane, all of c's box lies strictly above
/// every x's horizon, and no polygon may hide any of c's box from any x of R
/// (OcclusionCulling::may_hide_between). Then its term tau_c(x) = sum_A B_A FF(x, A) is the
/// unoccluded, unclipped integral of the kernel k(x, y) = P Q / (pi r^4) over its faces
/// (u = y - x, r = |u|, P = n . u the height of y over x's plane, Q = m' . u the height of x
/// over c's plane, m' = -c's normal), a smooth function of x on R. Clusters that contribute
/// nothing at any x of R (R behind their plane, or they lie wholly under R's horizons) are left
/// out, as the plain gather leaves them out; every other cluster is *rest*.
///
/// Its curvature. Along x(t) = x + t w (|w| = 1), with a = n . w, b = m' . w, s = u . w,
///   d^2/dt^2 (P Q r^-4) = 2 a b r^-4 - 8 (a Q + b P) s r^-6 - 4 P Q r^-6 + 24 P Q s^2 r^-8.
/// With |a| <= a_max (the segments' largest slope out of the plane, measured), |b| <= the
/// length of m's part in the plane plus a_max, |s| <= S (the largest in-plane distance between
/// the two boxes plus P_max a_max), P <= min(P_max, r), Q <= min(Q_max, r), every term is
/// non-increasing in r, so at r >= r_min (the distance between the boxes)
///   |d^2 k / dt^2| <= M = [2 a b + 8 (a Q + b P) S / r^2 + P Q max(4, 24 S^2 / r^2) / r^2]
///                         / (pi r^4)   at r = r_min, each of P, Q, S capped at r_min,
/// and |grad_x k| <= G = [(P + Q) + 4 P Q / r] / (pi r^4) likewise. Summed over the faces,
/// |tau_c''| <= bmax_c face_area_c M and |grad tau_c| <= bmax_c face_area_c G, per channel.
///
/// The interpolation. A point p of the tile is an affine combination p = sum l_i v_i + e of
/// three corners (barycentric in the plane; e the rounding residue, measured). By Taylor's
/// theorem at p along each segment [p, v_i] (inside R, where the smooth sum f = sum over the
/// smooth clusters is C^2), f(v_i) = f(p) + grad f(p) . (v_i - p) + R_i, |R_i| <=
/// M_f |v_i - p|^2 / 2, so with sum l_i = 1
///   |f(p) - sum l_i f(v_i)| <= M_f / 2 sum |l_i| |v_i - p|^2 + G_f |e|.
/// Each f(v_i) is gathered at the corner by clusters seen whole (a certified interval), so f(p)
/// lies in the interpolated interval widened by that error. The rest is gathered at p by the
/// plain cluster sum restricted to the rest, with the smooth part as a known interval: the
/// reported bound holds for H(p) = f(p) + rest(p), and the same stopping rule applies to it. A
/// point where the tile cannot meet the tolerance is gathered on its own (LocalPass::gather).
///
/// Which clusters are smooth enough is a matter of cost, not of correctness: the tile's cut
/// splits the smooth cluster with the largest curvature term until their sum is within half of
/// T times the darkest corner's H, and moves single faces that stay over it to the rest.
#include <array>
#include <span>
#include <vector>

#include "localpass/local_pass.h"

namespace rad {

/// The curvature and gradient bounds M and G above for one unit of B over one unit of area,
/// from the boxes around the tile (`region`, normal n) and a cluster (`box`, front normal
/// `normal`), with a_max the segments' slope out of the plane. Infinite when the boxes meet.
struct KernelVariation {
  double curvature = 0, gradient = 0;
  /// The kernel's largest value where P <= 1: times the region's depth along n, what the sliver
  /// of a unit area between the points' lowest and highest horizons can bring.
  double sliver = 0;
};
KernelVariation kernel_variation(const Eigen::AlignedBox3d& region, const Vec3& n,
                                 const Eigen::AlignedBox3d& box, const Vec3& normal, double a_max);

}  // namespace rad
