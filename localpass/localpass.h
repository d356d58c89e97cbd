#pragma once
/// Module `localpass` (rad_localpass): the error-bounded driver of paper 004 Fig. 6 (DESIGN.md
/// §1 step 3): at a point, split the faces by shaft culling over the octree into those nothing
/// can hide and groups that may be hidden (occlusion_culling.h, shaft.h), gather the groups in
/// order of decreasing bound through an exact gatherer, and stop at the tolerance with a
/// certified bound (local_pass.h); plane mirrors by chains unfolded into scenes of their own
/// (mirror_images.h, 000 §3, §5), and refraction through polyhedra by chains of facets unfolded
/// the same way at apparent depth, a heuristic kept apart from the bound (refraction_images.h,
/// 000 §4; the unfolding both share: unfolding.h); point lights, exactly
/// (point_light_visibility.h), and glossy transfer by 003's beams through a cone hierarchy, a
/// heuristic kept apart (glossy_transfer.h). Also the method names (method.h), the Monte
/// Carlo baseline (monte_carlo.h) and the path tracer of the scene itself, the reference
/// (path_tracer.h).
///
/// May use: octree, hemisphere, vertex, radiosity, scene, geometry.
#include "localpass/glossy_transfer.h"
#include "localpass/local_pass.h"
#include "localpass/method.h"
#include "localpass/mirror_images.h"
#include "localpass/monte_carlo.h"
#include "localpass/path_tracer.h"
#include "localpass/point_light_visibility.h"
#include "localpass/refraction_images.h"
#include "localpass/unfolding.h"
