// Fuzz target: a material library (.mtl), as an OBJ's mtllib reads it (scene/mtl.h).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "scene/error.h"
#include "scene/mtl.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> warnings;
  try {
    rad::parse_material_library(text, "fuzz.mtl", warnings);
  } catch (const rad::Error&) {
  }
  return 0;
}
