#pragma once
/// Module `render` (rad_render): images from the scene camera, one primary ray per pixel:
/// albedo and facing (albedo_render.h), the classic Gouraud display of a solution
/// (patch_render.h), and B = E + rho H through the local pass or the Monte Carlo baseline
/// (irradiance_render.h).
///
/// May use: localpass, octree, radiosity, scene, geometry, formats (the image type), distributed
/// (tiles over the processes of an MPI job), TBB.
#include "render/albedo_render.h"
#include "render/irradiance_render.h"
#include "render/patch_render.h"
