#pragma once
/// Reading polygon meshes (OBJ, PLY, OFF, STL) as polygon soups: every face in file order, with
/// its own vertices (the readers, and why they are ours: mesh_formats.h).
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/vec.h"
#include "scene/input_files.h"

namespace rad {

/// What an OBJ file says of its materials (mtl.h reads them): the material libraries it names
/// (`mtllib`, paths as written, relative to the OBJ's folder) and the material (`usemtl`) each
/// face was given. Empty for the other formats, which name none.
struct MeshMaterials {
  std::vector<std::string> libraries;
  std::vector<std::string> names;       ///< usemtl names, in order of first use
  std::vector<long long> first_line;    ///< the line of each name's first usemtl
  std::vector<int> face_name;           ///< per face: an index into names, or -1 before any
  std::vector<long long> library_line;  ///< the line of each library's mtllib
};

/// Reads the faces of a mesh file as vertex lists in file order (counter-clockwise = front).
/// `where` names the element for messages. Throws InputError when the file is missing,
/// unreadable, of an unsupported format, malformed (naming the line or element), or claims more
/// than the limits (scene/limits.h); what a reader skips (OBJ lines and curves, PLY elements
/// other than vertex and face) is appended to `warnings`. Faces are not validated here: a face
/// with too few vertices or non-finite coordinates comes back as it is, for polygon validation to
/// name. Non-manifold faces are kept. Cost: one pass over the file, which is held in memory.
/// With `files`, the bytes recorded there for `file` are read instead of the disk, and bytes
/// read from disk are recorded (scene/input_files.h). With `materials`, what an OBJ says of its
/// materials is stored there (nothing is read from its libraries).
std::vector<std::vector<Vec3>> read_mesh_faces(const std::filesystem::path& file,
                                               const std::string& where,
                                               std::vector<std::string>& warnings,
                                               InputFiles* files = nullptr,
                                               MeshMaterials* materials = nullptr);

/// True for the extensions read_mesh_faces accepts (case-insensitive): .obj .ply .off .stl
bool is_supported_mesh_extension(const std::filesystem::path& file);
/// True for the formats whose files name their faces' materials: .obj (MeshMaterials).
bool names_own_materials(const std::filesystem::path& file);

}  // namespace rad
