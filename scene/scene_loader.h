#pragma once
/// Loading and validating JSON scene files (DESIGN.md §5).
#include <filesystem>
#include <string>

#include "scene/input_files.h"
#include "scene/scene.h"

namespace rad {

/// Loads a scene file. Mesh paths are relative to the scene file's folder. Every polygon of the
/// result is validated (see make_polygons). Throws InputError naming the file and element for
/// anything malformed: unreadable file, invalid JSON, unknown key, wrong type, unknown material,
/// non-finite number (NaN/Infinity, which Python's json module writes), reflectance outside
/// [0, 1), negative emission, bad camera, and every polygon error class. With `files`, the scene
/// and its meshes are taken from there where recorded, and recorded there where read from disk
/// (scene/input_files.h).
Scene load_scene(const std::filesystem::path& file, InputFiles* files = nullptr);

/// Same as load_scene for JSON text already in memory; `file` is used for messages and to
/// resolve mesh paths.
Scene parse_scene(const std::string& json_text, const std::filesystem::path& file,
                  InputFiles* files = nullptr);

}  // namespace rad
