#pragma once
/// The solution file: VTK XML PolyData (.vtp) that ParaView opens as is (DESIGN.md §5).
///
/// Cells are the leaf elements (with T-vertices, so the mesh is conforming), with cell data
/// `radiosity`, `emission`, `reflectance` (RGB), `parent_polygon`, `patch`, `level`, `area`;
/// point data `vertex_radiosity` (Gouraud values). Field data carries what re-rendering needs
/// without solving again: the scene path and fingerprint, the solver settings and statistics
/// (JSON), the ambient term, the patches, and the exact element corners. Binary, appended, zlib
/// (lossless): reading a file back gives the same patches and values bit for bit.
#include <filesystem>

#include "radiosity/solution.h"
#include "scene/scene.h"

namespace rad {

/// Writes atomically (temporary file + rename). `scene` supplies materials for the cell data.
void write_solution(const std::filesystem::path& file, const Solution& solution,
                    const Scene& scene);

/// Reads a solution written by write_solution. Elements are the leaves (no tree). Throws
/// InputError naming the file and the missing or malformed array.
Solution read_solution(const std::filesystem::path& file);

}  // namespace rad
