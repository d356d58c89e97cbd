#pragma once
/// Module `reference` (rad_reference): what the local pass is measured against. The path
/// tracer of the scene itself, every bounce sampled (path_tracer.h): the reference of the whole
/// pipeline; and the Monte Carlo final gather over a solution's faces (monte_carlo.h): the
/// baseline users would otherwise pick. Neither knows the local pass.
///
/// May use: scene, geometry.
#include "reference/monte_carlo.h"
#include "reference/path_tracer.h"
