// Fuzz target: the OpenEXR images `radiosity compare` reads (RGB and named channels).
#include <cstdint>

#include "formats/image_io.h"
#include "fuzz/fuzz_target.h"
#include "scene/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = rad::fuzz::as_file(data, size, ".exr");
  try {
    rad::read_exr(path);
  } catch (const rad::Error&) {
  }
  try {
    rad::read_exr_channels(path);
  } catch (const rad::Error&) {
  }
  return 0;
}
