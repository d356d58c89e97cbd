// Fuzz target: the probe points CSV (`radiosity probe --points`).
#include <cstdint>

#include "formats/points_csv.h"
#include "fuzz/fuzz_target.h"
#include "scene/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = rad::fuzz::as_file(data, size, ".csv");
  try {
    rad::read_points_csv(path);
  } catch (const rad::Error&) {
  }
  return 0;
}
