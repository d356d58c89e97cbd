#pragma once
/// Module `hemisphere` (rad_hemisphere): the whole hemisphere-projection method (paper 004 §3;
/// DESIGN.md §4), one of the two exact gatherers:
///  - spherical_polygon.h: convex spherical polygons whose edges are stored as the normals of
///    their planes through x, exact splitting by such planes, intersection and difference;
///  - visible_surface.h: the visible-surface structure, a 2D BSP of great-circle planes through
///    x whose cells show the nearest polygon, built in any insertion order;
///  - hemisphere_gatherer.h: the gatherer (geometry/exact_gatherer.h) built on them.
///
/// May use: geometry (Eigen only).
#include "hemisphere/hemisphere_gatherer.h"
#include "hemisphere/spherical_polygon.h"
#include "hemisphere/visible_surface.h"
