#pragma once
/// Module `experiments` (rad_experiments): the accuracy-versus-tolerance experiment of paper 004
/// §5 (sweep.h), the relative error maps it measures (error_map.h), and the global solution
/// against a path-traced reference at chosen points (global_accuracy.h). The pictures of the
/// experiment are viz's (viz/sweep_figures.h).
///
/// May use: render, localpass, octree, radiosity, scene, geometry, formats, distributed.
#include "experiments/error_map.h"
#include "experiments/global_accuracy.h"
#include "experiments/sweep.h"
