#pragma once
/// Module `radiosity` (rad_radiosity): the coarse global solution (DESIGN.md §1 step 1).
/// Owns: meshing each input polygon into patches and elements (mesher.h), progressive
/// refinement radiosity in RGB with adaptive element refinement (Cohen, Chen, Wallace,
/// Greenberg 1988; solver.h), the solution's data model (solution.h), its elements as gatherer
/// faces (solution_faces.h), and the conforming OpenMesh half-edge mesh of its elements with
/// mean-value interpolation for display (patch_mesh.h). Form factors are geometry/lambert.h's.
///
/// May use: scene, geometry, OpenMesh, and TBB (the solver is parallel over receivers).
#include "radiosity/mesher.h"
#include "radiosity/patch_mesh.h"
#include "radiosity/solution.h"
#include "radiosity/solution_faces.h"
#include "radiosity/solver.h"
