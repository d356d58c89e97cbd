#pragma once
/// Module `localpass` (rad_localpass): the error-bounded driver of paper 004 Fig. 6 (DESIGN.md
/// §1 step 3): at a point, split the faces by shaft culling over the octree into those nothing
/// can hide and groups that may be hidden (occlusion_culling.h, shaft.h), gather the groups in
/// order of decreasing bound through an exact gatherer, and stop at the tolerance with a
/// certified bound (local_pass.h); what arrives by way of mirrors, refracting objects and
/// glossy surfaces through the unfolded scenes and beams of specular/; point lights, exactly
/// (point_light_visibility.h). Also the method names (method.h).
///
/// May use: specular, octree, hemisphere, vertex, radiosity, scene, geometry.
#include "localpass/local_pass.h"
#include "localpass/method.h"
#include "localpass/point_light_visibility.h"
