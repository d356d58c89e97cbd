#pragma once
// Shared by the fuzz targets: the bytes as a file of the reader's kind (the readers take paths,
// as the command line gives them), and the one outcome allowed besides success, an Error of
// ours. Anything else (a crash, a sanitizer report, another exception, a hang) is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

namespace rad::fuzz {

/// A file in the temporary folder holding `data`, named with this process's id and `extension`
/// (libFuzzer runs one input at a time per process).
inline std::filesystem::path as_file(const uint8_t* data, size_t size,
                                     const std::string& extension) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("rad-fuzz-" + std::to_string(::getpid()) + extension);
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, file) != size) std::abort();
  std::fclose(file);
  return path;
}

}  // namespace rad::fuzz
