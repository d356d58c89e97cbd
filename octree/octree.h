#pragma once
/// Module `octree` (rad_octree): the energy-bounded octree over the patches of a solution
/// (paper 004 §4; DESIGN.md §3 eqs. 5-9): leaves of roughly equal energy, Bmax per voxel, the
/// view-dependent bounds Bound(x, v) and their ordering for the local pass.
///
/// May use: radiosity, scene. Status: the target exists so the module graph is fixed; the code
/// comes with the local-pass issue.
#include "radiosity/radiosity.h"
