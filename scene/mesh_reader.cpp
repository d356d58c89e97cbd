#include "scene/mesh_reader.h"

#include <algorithm>
#include <cctype>
#include <fstream>

#include "scene/error.h"
#include "scene/input_files.h"
#include "scene/limits.h"
#include "scene/mesh_formats.h"

namespace rad {
namespace mesh_formats {

std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string read_model_file(const std::filesystem::path& file, const std::string& what,
                            const std::string& where, InputFiles* files) {
  if (const std::string* recorded = files ? files->find(file) : nullptr) return *recorded;
  try {
    check_input_file(file, what);
  } catch (const InputError& e) {
    throw InputError(where + ": " + e.what());
  }
  std::error_code error;
  std::ifstream in(file, std::ios::binary);
  if (!in.good()) throw InputError(where + ": cannot open " + what + " '" + file.string() + "'");
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (error || size > limits::kMeshFileBytes) {
    throw InputError(where + ": " + what + " '" + file.string() + "' is larger than the limit of " +
                     std::to_string(limits::kMeshFileBytes >> 20) + " MiB");
  }
  std::string bytes(size, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (static_cast<std::uintmax_t>(in.gcount()) != size) {
    throw InputError(where + ": cannot read " + what + " '" + file.string() + "'");
  }
  if (files) files->add(file, bytes);
  return bytes;
}

}  // namespace mesh_formats

using mesh_formats::lower_extension;

bool is_supported_mesh_extension(const std::filesystem::path& file) {
  const std::string ext = lower_extension(file);
  return ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl";
}

bool names_own_materials(const std::filesystem::path& file) {
  return lower_extension(file) == ".obj";
}

std::vector<std::vector<Vec3>> read_mesh_faces(const std::filesystem::path& file,
                                               const std::string& where,
                                               std::vector<std::string>& warnings,
                                               InputFiles* files, MeshMaterials* materials) {
  if (!is_supported_mesh_extension(file)) {
    throw InputError(where + ": unsupported mesh format '" + file.extension().string() + "' of '" +
                     file.string() + "' (supported: .obj .ply .off .stl)");
  }
  const std::string bytes = mesh_formats::read_model_file(file, "mesh file", where, files);

  const mesh_formats::MeshSource source{bytes, file.string(), where};
  std::vector<std::vector<Vec3>> faces;
  const std::string ext = lower_extension(file);
  MeshMaterials unused;
  if (ext == ".obj")
    faces = mesh_formats::read_obj(source, warnings, materials ? *materials : unused);
  if (ext == ".ply") faces = mesh_formats::read_ply(source, warnings);
  if (ext == ".off") faces = mesh_formats::read_off(source);
  if (ext == ".stl") faces = mesh_formats::read_stl(source);
  if (faces.empty()) {
    throw InputError(where + ": mesh file '" + file.string() + "' has no readable faces");
  }
  return faces;
}

}  // namespace rad
