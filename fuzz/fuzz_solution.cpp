// Fuzz target: the solution file (VTK XML PolyData, `radiosity solve -o`), as render, probe and
// export read it.
#include <cstdint>

#include "formats/solution_io.h"
#include "fuzz/fuzz_target.h"
#include "scene/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = rad::fuzz::as_file(data, size, ".vtp");
  try {
    rad::read_solution(path);
  } catch (const rad::Error&) {
  }
  return 0;
}
