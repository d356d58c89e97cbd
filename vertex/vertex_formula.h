#pragma once
/// Stark's vertex-based form factor (paper 001 eqs. 6-8): the irradiance from a uniformly
/// emitting polygon as a sum over its vertices projected onto the plane one unit above the
/// receiver, each vertex contributing through the slopes of its incoming and outgoing edges.
/// It is the kernel of vertex tracing, where only apparent vertices are visited.
#include <vector>

#include "geometry/vec.h"

namespace rad {

/// F(x, y, m) = (A x / 2) atan(A y) + (C (y - m x) / 2) atan(C (x + m y)),
/// A = 1 / sqrt(1 + x^2), C = 1 / sqrt(1 + m^2 + (y - m x)^2)   (001 eqs. 7-8).
double stark_F(double x, double y, double m);

/// The part of F that depends on m (its second term). Where neither incident edge of a vertex
/// is vertical the first terms cancel exactly, and dropping them avoids subtracting two equal
/// numbers (001 §3.1: "the terms do cancel if neither incident edge is vertical").
double stark_F_slope_term(double x, double y, double m);

/// One projected vertex's contribution to pi * FF: F(x, y, m_in) - F(x, y, m_out) with the
/// cancelling first terms left out; a vertical edge (undefined slope) contributes no F at all
/// (001 eq. 6). `in_vertical` / `out_vertical` say which incident edges are vertical.
double stark_vertex_term(double x, double y, double m_in, bool in_vertical, double m_out,
                         bool out_vertical);

/// The m-dependent term of F written with the unit normal k of the edge's plane through x
/// instead of its projected slope and intercept: the projected edge lies on the line
/// k_x X + k_y Y + k_z = 0, i.e. m = -k_x / k_y and b = -k_z / k_y, and then
///   stark_F_slope_term(x, y, m) = -(k_z / 2) atan(k_y x - k_x y),
/// whatever k's sign. This form needs no slope and no intercept (which a far-projected vertex
/// computes as the difference of two huge numbers), is continuous as the edge turns vertical,
/// and at a vertical edge (k_y = 0) equals minus F's first term, so the paper's omission of
/// vertical edges happens by itself.
double stark_G(double x, double y, const Vec3& k);

/// Height of the horizon clip, relative to the polygon's largest distance from x: the
/// projection of a point at height z is 1/z away, so a polygon reaching the tangent plane must
/// be cut slightly above it (at 0 the projection is infinite). The neglected sliver costs
/// O((h / r)^2) with r the distance from x of the crossing edge: measured 3e-13 at 1e-8 for a
/// crossing 0.02 from x, 4e-17 at 1e-12. With the plane-normal form of the vertex terms
/// (stark_G) the projected coordinates of ~1e12 are harmless, so the clip sits at 1e-12.
constexpr double kStarkHorizon = 1e-12;

/// The unoccluded form factor of a planar polygon (any orientation: the absolute value is
/// taken; one-sidedness is the caller's) for a differential receiver at x with unit normal n,
/// by Stark's vertex sum (001 eq. 6) after projecting onto the plane one unit above x along n:
/// FF = |sum_i G(v_i, k_in) - G(v_i, k_out)| / pi, with k the edges' plane normals computed in
/// 3D before projection (see stark_G). The polygon is first clipped at the height
/// kStarkHorizon * (its largest distance from x) above x's tangent plane. Measured against
/// Lambert's formula (tests/localpass/vertex_formula_test.cpp): 2.4e-15 worst over 5000 random
/// convex and concave polygons, many crossing the horizon; on a polygon of size s at unit
/// distance the vertex terms (order s) cancel to a result of order s^2, so the relative error
/// is ~5e-17 / s (4.7e-11 at s = 1e-6, 4.6e-8 at 1e-9). Cost O(#V).
double stark_form_factor(const Vec3& x, const Vec3& n, const std::vector<Vec3>& polygon);

}  // namespace rad
