#pragma once
/// Loading and validating scene files (DESIGN.md §5): JSON, or a mesh file alone.
#include <filesystem>
#include <string>

#include "scene/input_files.h"
#include "scene/scene.h"

namespace rad {

/// How a scene is loaded beyond what its files say.
struct SceneOptions {
  /// Reverse every polygon's vertex order, which turns its front side (--flip-normals: a room
  /// modelled from outside has its fronts facing out of it).
  bool flip_normals = false;
};

/// Loads a scene file (JSON); a mesh file (.obj .ply .off .stl) alone is a scene too (mesh_scene
/// in mesh_object.h: an OBJ's faces with the materials of its libraries, a camera from its
/// bounds). Mesh paths are relative to the scene file's folder. Every polygon of the
/// result is validated (see make_polygons). Throws InputError naming the file and element for
/// anything malformed: unreadable file, invalid JSON, unknown key, wrong type, unknown material,
/// non-finite number (NaN/Infinity, which Python's json module writes), reflectance outside
/// [0, 1), negative emission, bad camera, and every polygon error class. With `files`, the scene
/// and its meshes are taken from there where recorded, and recorded there where read from disk
/// (scene/input_files.h). Warns (Scene::warnings) of what loading fixed, and when no polygon
/// faces a light (check_facing in scene_checks.h).
Scene load_scene(const std::filesystem::path& file, InputFiles* files = nullptr,
                 const SceneOptions& options = {});

/// Same as load_scene for JSON text already in memory; `file` is used for messages and to
/// resolve mesh paths.
Scene parse_scene(const std::string& json_text, const std::filesystem::path& file,
                  InputFiles* files = nullptr, const SceneOptions& options = {});

}  // namespace rad
