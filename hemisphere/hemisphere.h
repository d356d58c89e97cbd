#pragma once
/// Module `hemisphere` (rad_hemisphere): pure geometry on the unit sphere around a point x
/// (paper 004 §3; DESIGN.md §4). Owns:
///  - spherical_polygon.h: convex spherical polygons whose edges are stored as the normals of
///    their planes through x, exact splitting by such planes, intersection and difference,
///    clipping at x's tangent plane in 3D, and Lambert's contour formula (also with holes);
///  - visible_surface.h: the visible-surface structure, a 2D BSP of great-circle planes through
///    x whose cells show the nearest polygon, built in any insertion order.
///
/// May use: Eigen only.
#include "hemisphere/spherical_polygon.h"
#include "hemisphere/visible_surface.h"
