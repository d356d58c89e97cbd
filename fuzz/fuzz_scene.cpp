// Fuzz target: the scene file (JSON with its materials, objects and camera), as parse_scene
// reads it. Meshes named by a fuzzed scene resolve against the temporary folder, so mostly
// "cannot open mesh file": the mesh readers have their own targets.
#include <cstdint>
#include <string>

#include "scene/error.h"
#include "scene/scene_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    rad::parse_scene(std::string(reinterpret_cast<const char*>(data), size), "/tmp/fuzz.json");
  } catch (const rad::Error&) {
  }
  return 0;
}
