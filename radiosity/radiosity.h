#pragma once
/// Module `radiosity` (rad_radiosity): the coarse global solution (DESIGN.md §1 step 1).
/// Owns: meshing each input polygon into patches and elements (mesher.h), point-to-polygon form
/// factors (form_factor.h), progressive refinement radiosity in RGB with adaptive element
/// refinement (Cohen, Chen, Wallace, Greenberg 1988; solver.h), the solution's data model
/// (solution.h), and the conforming OpenMesh half-edge mesh of its elements with mean-value
/// interpolation for display (patch_mesh.h).
///
/// May use: scene, and TBB (the solver is parallel over receivers).
#include "radiosity/form_factor.h"
#include "radiosity/mesher.h"
#include "radiosity/patch_mesh.h"
#include "radiosity/solution.h"
#include "radiosity/solver.h"
