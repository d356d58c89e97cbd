#pragma once
/// Module `geometry` (rad_geometry): the geometry kernel at the bottom of the graph, each
/// operation written once:
///  - vec.h: the vector types (Vec2, Vec3, Rgb);
///  - clip.h: clipping a polygon to a half-space (Sutherland-Hodgman);
///  - lambert.h: Lambert's contour formula and the unoccluded point-to-polygon form factor;
///  - plane.h: facing tests (which side of a plane a point is on);
///  - planar.h: the planar kernel (Newell, plane frames, 2D area, hull, triangulation, ...);
///  - box_tree.h: a hierarchy of axis-aligned boxes (2D and 3D), for queries and culling;
///  - tolerance.h: the scene's tolerance policy, one value for the gatherers and the culling;
///  - emitting_face.h: the faces the exact gatherers take;
///  - exact_gatherer.h: the one interface of the two exact gatherers;
///  - refraction.h: the optics of a flat interface (Snell, apparent depth, Fresnel; 000 §4);
///  - glossy_beam.h: one point light's glossy beam through one triangle (003 §4).
///
/// May use: Eigen only.
#include "geometry/box_tree.h"
#include "geometry/clip.h"
#include "geometry/emitting_face.h"
#include "geometry/exact_gatherer.h"
#include "geometry/glossy_beam.h"
#include "geometry/lambert.h"
#include "geometry/planar.h"
#include "geometry/plane.h"
#include "geometry/refraction.h"
#include "geometry/tolerance.h"
#include "geometry/vec.h"
