#pragma once
/// Angular spans (paper 001 §3.2, Fig. 5, eq. 9): the picture around one traced vertex, as the
/// circular list of sectors each showing the nearest polygon with its emission. The vertex's
/// contribution to pi x irradiance is sum over boundaries of (M after - M before) x F(x, y,
/// tan theta); F's m-independent term cancels around the circle, and the rest is stark_G with
/// the boundary's plane through x, taken through the vertex itself (the "snap" of 001 §5).
///
/// Everything is in the image plane one unit above x (x at the origin, receiver normal +z): the
/// vertex is q = (d_x / d_z, d_y / d_z). A boundary is the line of a plane k through x (unit
/// normal, from the feature's 3D endpoints); its image direction is (k_y, -k_x) (the image of
/// the tangent k x d), exact even where q is ~1e8 from the origin at the image square.
/// G takes k itself, not a line re-fitted through q: q's rounding there (~1e-4 absolute) would
/// move the line's offset by as much. Sectors run counter-clockwise; the branch cut at pi is
/// handled by sorting on the circle.
#include <span>

#include "geometry/vec.h"

namespace rad {

/// One polygon's part in the list: a full span (the ray hits its interior), an edge span (the
/// ray crosses an edge: the polygon covers the half-plane to the left of the direction
/// (k_y, -k_x) of `start`), or a vertex span (the sector counter-clockwise from the direction
/// (k_y, -k_x) of `start` to the direction -(k_y, -k_x) of `end`).
struct SpanEntry {
  enum class Kind { full, edge, vertex };
  Kind kind = Kind::full;
  Vec3 start = Vec3::Zero();  ///< Plane of the boundary where the polygon begins (edge, vertex).
  Vec3 end = Vec3::Zero();    ///< Plane where it ends (vertex spans; an edge span ends on `start`).
  Vec3 normal = Vec3::Zero();  ///< Unit normal of the polygon's plane (x at the origin)...
  double offset = 0;           ///< ...and normal . p on it (never 0: edge-on planes are dropped).
  int order = 0;  ///< Coplanar overlap: the lower order shows (as in hemi::VisibleSurface).
  Rgb exitance = Rgb::Zero();  ///< M: what it radiates towards x (0 when x sees its back).
  /// What it passes of what lies behind it, from either side (a filter, 000 §2.2); 0: opaque.
  Rgb transmittance = Rgb::Zero();
};

/// Distance of image point q from the line of plane k through x, relative to 1 + |q| (so a
/// tolerance means the same near the zenith and next to the horizon, where q is far out).
double relative_line_distance(const Vec3& k, const Vec2& q);

/// Depth ties: two planes whose equal-depth plane through x (m = c_F n_Q - c_Q n_F) passes
/// within `radius` (relative_line_distance) of q are taken to meet on the ray; their order then
/// changes across that plane, which becomes one more boundary (the projected intersection line
/// of two touching or interpenetrating polygons). Farther off, the one nearer along d is nearer
/// in the whole cone.
///
/// In each sector the entries covering it are composed front to back (000 §2.2): M = M_1 +
/// T_1 (M_2 + T_2 (M_3 + ...)), ending at the first opaque one; with no filters that is the
/// nearest entry's M, as in 001.
///
/// Returns sum over boundaries of (M_after - M_before) G(q, boundary plane): pi times the
/// vertex's contribution to the irradiance (001 eq. 9). No entries, or full spans alone, give 0.
Rgb angular_span_sum(const Vec3& d, std::span<const SpanEntry> entries, double radius);

}  // namespace rad
