#pragma once
/// Module `radiosity` (rad_radiosity): the coarse global solution. Owns: meshing each input
/// polygon into patches and elements as an OpenMesh half-edge mesh (keeping the connectivity
/// vertex tracing needs), point-to-polygon form factors, and progressive refinement radiosity
/// (Cohen, Chen, Wallace, Greenberg 1988) in RGB (DESIGN.md §1 step 1).
///
/// May use: scene. Status: the target exists so the module graph is fixed; the code comes with
/// the progressive-radiosity issue.
#include "scene/scene.h"
