#pragma once
/// Module `localpass` (rad_localpass): everything that runs per pixel or per probe point
/// (paper 004 Fig. 6; DESIGN.md §1 step 3): the error-bounded driver that gathers voxel by voxel
/// and stops at the tolerance, the hemisphere gatherer, the vertex-tracing gatherer (paper 001),
/// a Monte Carlo baseline, the primary-ray renders (albedo, facing) and the classic Gouraud display
/// of a solution (patches).
///
/// May use: octree, hemisphere, radiosity, scene, TBB.
#include "localpass/albedo_render.h"
#include "localpass/image.h"
#include "localpass/patch_render.h"
