#pragma once
/// Module `specular` (rad_specular): light that arrives by way of specular surfaces, as scenes
/// the exact gatherers can take. Plane mirrors (000 §3, §5) by chains of mirror pieces unfolded
/// into scenes of their own (mirror_images.h), refraction through polyhedra (000 §4) by chains
/// of facets unfolded at apparent depth, a heuristic kept apart from the bound
/// (refraction_images.h), both through the one unfolding (unfolding.h); and paper 003's glossy
/// transfer by backward beams through a cone hierarchy, a heuristic kept apart
/// (glossy_transfer.h). The local pass (localpass/) drives them.
///
/// May use: scene, geometry.
#include "specular/glossy_transfer.h"
#include "specular/mirror_images.h"
#include "specular/refraction_images.h"
#include "specular/unfolding.h"
