#pragma once
/// Reading polygon meshes: OBJ, PLY and OFF through OpenMesh; STL by a reader of our own that
/// keeps every facet (see mesh_reader.cpp).
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/vec.h"

namespace rad {

/// Reads the faces of a mesh file as vertex lists in file order (counter-clockwise = front).
/// `where` names the element for messages. Throws InputError when the file is missing,
/// unreadable, or of an unsupported format, and when a face cannot be read (it would be lost);
/// OpenMesh's other remarks are appended to `warnings`. Non-manifold faces are kept.
std::vector<std::vector<Vec3>> read_mesh_faces(const std::filesystem::path& file,
                                               const std::string& where,
                                               std::vector<std::string>& warnings);

/// True for the extensions read_mesh_faces accepts (case-insensitive): .obj .ply .off .stl
bool is_supported_mesh_extension(const std::filesystem::path& file);

}  // namespace rad
