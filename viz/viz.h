#pragma once
/// Module `viz` (rad_viz): files people look at. OpenEXR images and PNG previews now; later VTK
/// files for ParaView (patch meshes, octree, error maps), charts, and the solution file.
///
/// May use: every module above it (localpass, octree, radiosity, hemisphere, scene), VTK,
/// OpenEXR.
#include "viz/atomic_file.h"
#include "viz/image_io.h"
