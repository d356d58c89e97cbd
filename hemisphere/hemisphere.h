#pragma once
/// Module `hemisphere` (rad_hemisphere): pure geometry on the unit hemisphere above a point x
/// with normal N (paper 004 §3, DESIGN.md §4). Owns: clipping polygons at x's tangent plane,
/// spherical polygons whose edges are stored as great-circle plane normals, point-in-polygon and
/// arc-arc predicates, Weiler-Atherton boolean operations on the sphere, Lambert's contour
/// formula for the form factor of a spherical polygon with holes, and the front-to-back
/// visible-surface structure with its 2D BSP of great-circle planes.
///
/// May use: Eigen only. Status: the target exists so the module graph is fixed; the code comes
/// with the hemisphere-projection issue.
