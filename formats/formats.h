#pragma once
/// Module `formats` (rad_formats): the files users read and write (DESIGN.md §5): the image
/// type and OpenEXR / PNG preview files (image.h, image_io.h), the solution file as VTK XML
/// PolyData (solution_io.h), probe points and results as CSV (points_csv.h), a render's stats
/// JSON (render_stats.h), and writing through a temporary file and a rename (atomic_file.h).
///
/// May use: radiosity, scene, geometry, OpenEXR, VTK (file I/O), nlohmann-json.
#include "formats/atomic_file.h"
#include "formats/image.h"
#include "formats/image_io.h"
#include "formats/points_csv.h"
#include "formats/render_stats.h"
#include "formats/solution_io.h"
