#pragma once
/// Cutting polygons along their contact lines before they are meshed.
#include <vector>

#include "geometry/vec.h"
#include "scene/scene.h"

namespace rad {

/// The convex pieces of scene polygon `index` (counter-clockwise from its front, in its plane),
/// cut along every segment where another polygon rises from its front: the foot of a block
/// standing on a floor, a wall passing through it. Radiosity jumps there, from lit to buried or
/// to a contact shadow (Heckbert 1992's D0 discontinuities; Lischinski, Tampieri, Greenberg
/// 1992), and a patch or element straddling the line would average the two sides: its live
/// part is then too dark wherever it shoots, and too bright or too dark where a point near the
/// contact gathers from it. Each segment cuts the pieces it crosses along the line through it
/// (a convex piece is cut only by chords). Segments on the polygon's outline, and polygons
/// behind it or in its plane, cut nothing. Empty when nothing cuts the polygon. At most `max_cuts`
/// segments are used, the longest first.
std::vector<std::vector<Vec3>> contact_pieces(const Scene& scene, int index, int max_cuts = 64);

}  // namespace rad
