#pragma once
/// Module `viz` (rad_viz): what people look at: VTK files for ParaView (vtk_export.h: patch
/// mesh, octree, per-pixel stats), charts and heat maps as PNG (charts.h, error_heat_map.h), the
/// sweep's figures (sweep_figures.h), and the private X display VTK's rendering needs
/// (offscreen_display.h).
///
/// May use: experiments, render, localpass, octree, formats, radiosity, scene, geometry,
/// distributed, VTK.
#include "viz/charts.h"
#include "viz/error_heat_map.h"
#include "viz/offscreen_display.h"
#include "viz/sweep_figures.h"
#include "viz/vtk_export.h"
