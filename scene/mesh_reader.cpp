#include "scene/mesh_reader.h"

#include <algorithm>
#include <cctype>
#include <fstream>

#include "scene/error.h"
#include "scene/input_files.h"
#include "scene/limits.h"
#include "scene/mesh_formats.h"

namespace rad {
namespace {

std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// The whole of a mesh file, within limits::kMeshFileBytes.
std::string read_mesh_bytes(const std::filesystem::path& file, const std::string& where) {
  try {
    check_input_file(file, "mesh file");
  } catch (const InputError& e) {
    throw InputError(where + ": " + e.what());
  }
  std::error_code error;
  std::ifstream in(file, std::ios::binary);
  if (!in.good() || !std::filesystem::is_regular_file(file, error)) {
    throw InputError(where + ": cannot open mesh file '" + file.string() + "'");
  }
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (error || size > limits::kMeshFileBytes) {
    throw InputError(where + ": mesh file '" + file.string() + "' is larger than the limit of " +
                     std::to_string(limits::kMeshFileBytes >> 20) + " MiB");
  }
  std::string bytes(size, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (static_cast<std::uintmax_t>(in.gcount()) != size) {
    throw InputError(where + ": cannot read mesh file '" + file.string() + "'");
  }
  return bytes;
}

}  // namespace

bool is_supported_mesh_extension(const std::filesystem::path& file) {
  const std::string ext = lower_extension(file);
  return ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl";
}

std::vector<std::vector<Vec3>> read_mesh_faces(const std::filesystem::path& file,
                                               const std::string& where,
                                               std::vector<std::string>& warnings,
                                               InputFiles* files) {
  if (!is_supported_mesh_extension(file)) {
    throw InputError(where + ": unsupported mesh format '" + file.extension().string() + "' of '" +
                     file.string() + "' (supported: .obj .ply .off .stl)");
  }
  const std::string* recorded = files ? files->find(file) : nullptr;
  const std::string bytes = recorded ? *recorded : read_mesh_bytes(file, where);
  if (files && !recorded) files->add(file, bytes);

  const mesh_formats::MeshSource source{bytes, file.string(), where};
  std::vector<std::vector<Vec3>> faces;
  const std::string ext = lower_extension(file);
  if (ext == ".obj") faces = mesh_formats::read_obj(source, warnings);
  if (ext == ".ply") faces = mesh_formats::read_ply(source, warnings);
  if (ext == ".off") faces = mesh_formats::read_off(source);
  if (ext == ".stl") faces = mesh_formats::read_stl(source);
  if (faces.empty()) {
    throw InputError(where + ": mesh file '" + file.string() + "' has no readable faces");
  }
  return faces;
}

}  // namespace rad
