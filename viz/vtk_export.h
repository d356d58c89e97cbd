#pragma once
/// VTK XML files for ParaView beyond the solution file (DESIGN.md §5): the octree as hexahedra,
/// per-pixel statistics of a render as an image, and a picture of the patch mesh.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "octree/octree.h"
#include "radiosity/solution.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace rad {

/// The octree's non-empty voxels (inner and leaf) as VTK_HEXAHEDRON cells of an unstructured
/// grid (.vtu), on their octree cells. Cell data: `bmax` (RGB, eq. 5), `bmax_max` (its largest
/// channel, to colour by), `patch_count` (items in the voxel and below), `energy` (sum over those
/// items of area x largest radiosity channel: the power they radiate, W for metres), `level`,
/// `leaf` (1 for leaves: threshold on it to see the leaves alone). Atomic. Throws Error.
void write_octree_vtu(const std::filesystem::path& file, const Octree& octree);

/// Per-pixel arrays (each width x height, rows from the top) as point data of a VTK image
/// (.vti) with unit spacing, row 0 of the arrays at the top of the picture (y = height - 1).
/// Atomic. Throws Error when an array has the wrong size.
void write_pixel_image_vti(const std::filesystem::path& file, int width, int height,
                           const std::map<std::string, std::vector<float>>& arrays);

/// A picture of the patch mesh from `camera` (perspective, the scene camera's frame and field
/// of view): each element flat-shaded with its radiosity (linear x 2^exposure, clamped,
/// sRGB-encoded, as previews are; without an exposure, auto_exposure of the elements'
/// brightest channels) and the element edges drawn thin and dark. RGB PNG of the camera's
/// size. Needs an X display (started if missing). Throws Error.
void write_patch_mesh_png(const std::filesystem::path& file, const Solution& solution,
                          const Scene& scene, const CameraSpec& camera,
                          std::optional<double> exposure = std::nullopt);

}  // namespace rad
