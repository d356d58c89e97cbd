#pragma once
/// Module `radiosity` (rad_radiosity): the coarse global solution (DESIGN.md §1 step 1).
/// Owns: cutting polygons along their contact lines (contact_cuts.h) and meshing them into
/// patches and elements (mesher.h), progressive refinement radiosity in RGB with adaptive
/// element refinement (Cohen, Chen, Wallace, Greenberg 1988; solver.h, its state and steps in
/// progressive_solver.h, split over solver.cpp and refinement.cpp): what a shot delivers to
/// a point (shooter.h), the near field shot piece by piece (near_field.h), the form factors kept
/// across shots (form_factor_store.h), the shadow culling (shadow_culling.h), the jitter
/// streams (random_stream.h); the solution's data model (solution.h), its elements as gatherer
/// faces (solution_faces.h), and the conforming OpenMesh half-edge mesh of its elements with
/// mean-value interpolation for display (patch_mesh.h). Form factors are geometry/lambert.h's.
///
/// May use: scene, geometry, OpenMesh, and TBB (the solver is parallel over receivers).
#include "radiosity/contact_cuts.h"
#include "radiosity/form_factor_store.h"
#include "radiosity/mesher.h"
#include "radiosity/near_field.h"
#include "radiosity/patch_mesh.h"
#include "radiosity/random_stream.h"
#include "radiosity/shadow_culling.h"
#include "radiosity/shooter.h"
#include "radiosity/solution.h"
#include "radiosity/solution_faces.h"
#include "radiosity/solver.h"
