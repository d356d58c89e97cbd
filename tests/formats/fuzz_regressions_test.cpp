// The fuzz targets' regression set (fuzz/regressions/<target>/: every crash or hang a fuzzer
// found, and the issue's own cases), replayed through the same readers in the normal and the
// sanitized suites: each input is read or refused with an Error of ours, nothing else.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <typeinfo>

#include "formats/image_io.h"
#include "formats/points_csv.h"
#include "formats/solution_io.h"
#include "scene/error.h"
#include "scene/mesh_reader.h"
#include "scene/scene_loader.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

/// The reader each target fuzzes (fuzz/fuzz_*.cpp), given the input file.
const std::map<std::string, std::function<void(const fs::path&)>>& readers() {
  // The mesh readers choose by extension, which the stored inputs lack (the fuzz target adds
  // it, fuzz/fuzz_mesh.cpp): each is read as a copy with its target's extension.
  const auto read_mesh_as = [](const char* extension) {
    return [extension](const fs::path& f) {
      const fs::path copy =
          fs::temp_directory_path() / ("rad_fuzz_regression_" + f.filename().string() + extension);
      fs::copy_file(f, copy, fs::copy_options::overwrite_existing);
      std::vector<std::string> warnings;
      try {
        read_mesh_faces(copy, "m", warnings);
      } catch (...) {
        fs::remove(copy);
        throw;
      }
      fs::remove(copy);
    };
  };
  static const std::map<std::string, std::function<void(const fs::path&)>> all{
      {"fuzz_scene",
       [](const fs::path& f) {
         std::ifstream in(f, std::ios::binary);
         std::stringstream text;
         text << in.rdbuf();
         parse_scene(text.str(), f);
       }},
      {"fuzz_mesh_obj", read_mesh_as(".obj")},
      {"fuzz_mesh_ply", read_mesh_as(".ply")},
      {"fuzz_mesh_off", read_mesh_as(".off")},
      {"fuzz_mesh_stl", read_mesh_as(".stl")},
      {"fuzz_points", [](const fs::path& f) { read_points_csv(f); }},
      {"fuzz_solution", [](const fs::path& f) { read_solution(f); }},
      {"fuzz_exr",
       [](const fs::path& f) {
         try {
           read_exr(f);
         } catch (const Error&) {
         }
         read_exr_channels(f);
       }},
  };
  return all;
}

TEST(FuzzRegressions, EveryStoredInputIsReadOrRefusedWithOurError) {
  const fs::path root = fs::path(RAD_SOURCE_DIR) / "fuzz" / "regressions";
  int replayed = 0;
  for (const auto& [target, read] : readers()) {
    if (!fs::is_directory(root / target)) continue;
    for (const auto& entry : fs::directory_iterator(root / target)) {
      ++replayed;
      try {
        read(entry.path());
      } catch (const Error&) {  // refused with a message of ours: fine
      } catch (const std::exception& e) {
        ADD_FAILURE() << entry.path() << ": " << typeid(e).name() << ": " << e.what();
      }
    }
  }
  EXPECT_GE(replayed, 10) << "the regression set is missing";
}

}  // namespace
}  // namespace rad
