// Fuzz target: a mesh file of one format (RAD_MESH_EXTENSION: ".obj", ".ply", ".off" or
// ".stl"; one executable per format), as a scene's "mesh" key reads it.
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/fuzz_target.h"
#include "scene/error.h"
#include "scene/mesh_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = rad::fuzz::as_file(data, size, RAD_MESH_EXTENSION);
  std::vector<std::string> warnings;
  try {
    rad::read_mesh_faces(path, "objects[0]", warnings);
  } catch (const rad::Error&) {
  }
  return 0;
}
