#pragma once
/// A fresh, empty folder under the system's temporary folder, for a test's output files.
#include <filesystem>
#include <string>

namespace rad::test {

inline std::filesystem::path scratch_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("rad_test_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace rad::test
