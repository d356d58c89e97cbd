// Malformed and hostile inputs through the executable (issue 16): every class of
// tests/hostile_inputs.h and tests/bad_scene_cases.h exits 1 with one line naming the file and
// the problem: no crash, no hang, no escape codes, nothing written. With RAD_ROBUSTNESS_TABLE set
// to a path, also writes the table of docs/robustness.md (make docs): each class and the message
// it gets, with the folders as placeholders.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "formats/solution_io.h"
#include "scene/scene_loader.h"
#include "tests/bad_scene_cases.h"
#include "tests/cli/run_cli.h"
#include "tests/hostile_inputs.h"

namespace {

using namespace rad::test::cli;
const fs::path kRoot = RAD_SOURCE_DIR;
const fs::path kData = RAD_TEST_DATA;

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
}

/// A scene of one object, the mesh file `mesh` (copied from `source` when given).
void write_mesh_scene(const fs::path& dir, const std::string& mesh, const fs::path& source = {}) {
  if (!source.empty()) fs::copy_file(source, dir / mesh, fs::copy_options::overwrite_existing);
  std::ofstream(dir / (fs::path(mesh).stem().string() + ".json"))
      << R"({"materials": {"m": {}}, "objects": [{"material": "m", "mesh": ")" << mesh << "\"}]}";
}

/// The generated inputs, too large or too odd to commit, and scenes around the fuzzers' mesh
/// findings (stored without an extension, as the fuzz targets take them).
void write_generated_inputs(const fs::path& dir) {
  const fs::path found = kRoot / "fuzz/regressions";
  write_mesh_scene(
      dir, "obj_fuzz_crash.obj",
      found / "fuzz_mesh_obj/fuzz_mesh_obj-crash-c4beedf2e7b6187a905b9a4c94545ffee5b8ef9b");
  write_mesh_scene(
      dir, "ply_fuzz_timeout.ply",
      found / "fuzz_mesh_ply/fuzz_mesh_ply-timeout-c6417da4a95f481c74741673b6835f0b7a7a1494");
  {
    // Binary OFF: big-endian int32 counts (500 million vertices) and nothing else.
    std::string bytes = "OFF BINARY\n";
    for (const uint32_t count : {500'000'000u, 1u, 0u}) {
      for (int shift = 24; shift >= 0; shift -= 8) bytes += static_cast<char>(count >> shift);
    }
    std::ofstream(dir / "off_binary_claims.off", std::ios::binary) << bytes;
    write_mesh_scene(dir, "off_binary_claims.off");
  }
  std::ofstream(dir / "obj_long_word.obj") << "v " << std::string(100000, 'x') << " 0 0\n";
  write_mesh_scene(dir, "obj_long_word.obj");
  std::ofstream(dir / "deep.json") << std::string(100000, '[');
  {
    std::ofstream many(dir / "many_vertices.json");
    many << R"({"materials": {"w": {"reflectance": 0.5}}, "objects": [{"material": "w", )"
         << R"("polygons": [[)";
    for (int i = 0; i <= 100000; ++i) many << (i ? "," : "") << "[" << i << ",0,0]";
    many << "]]}]}";
  }
  {
    // A sparse file of 257 MiB: the size check must refuse it before reading a byte.
    std::ofstream(dir / "huge.json") << "{";
    fs::resize_file(dir / "huge.json", (257u << 20));
  }
}

TEST(HostileInput, EveryClassExitsOneWithOneLineAndWritesNothing) {
  const fs::path work = scratch();
  const fs::path inputs = work / "in", outputs = work / "out";
  fs::create_directories(inputs);
  write_generated_inputs(inputs);
  const Result solved =
      run("solve " + quoted(kRoot / "data/cornell-box/scene.json") +
          " --patch-size 0.25 --refine-threshold 0 -o " + quoted(work / "solution.vtp"));
  ASSERT_EQ(solved.exit_code, 0) << solved.err;
  {
    // Solutions of the right scene with values no solve writes: a polygon the scene lacks, a
    // NaN radiosity. Both pass the file's layout checks; the values must be refused.
    const rad::Scene scene = rad::load_scene(kRoot / "data/cornell-box/scene.json");
    rad::Solution wrong = rad::read_solution(work / "solution.vtp");
    rad::Scene larger = scene;  // the writer meshes by polygon: give it the one named
    larger.polygons.push_back(scene.polygons.back());
    wrong.elements[0].polygon = static_cast<int>(scene.polygons.size());
    rad::write_solution(inputs / "wrong_polygon.vtp", wrong, larger);
    rad::Solution nan = rad::read_solution(work / "solution.vtp");
    nan.elements[1].radiosity.y() = std::numeric_limits<double>::quiet_NaN();
    rad::write_solution(inputs / "nan_radiosity.vtp", nan, scene);
  }

  std::string table = "| input | message (exit 1) |\n|---|---|\n";
  const auto check = [&](const std::string& what, std::string command, const std::string& names,
                         const std::string& problem) {
    fs::remove_all(outputs);
    fs::create_directories(outputs);
    replace_all(command, "{h}", (kData / "hostile").string());
    replace_all(command, "{b}", (kData / "bad").string());
    replace_all(command, "{d}", (kRoot / "data").string());
    replace_all(command, "{s}", (work / "solution.vtp").string());
    replace_all(command, "{g}", inputs.string());
    replace_all(command, "{f}", (kRoot / "fuzz/regressions").string());
    replace_all(command, "{o}", outputs.string());
    const Result r = run(command, 120);
    EXPECT_EQ(r.exit_code, 1) << what << ": radiosity " << command << "\n" << r.err;
    // One line of error; the scene's own warnings (the Cornell box has one) may come first.
    std::string error;
    int lines = 0;
    std::istringstream stream(r.err);
    for (std::string line; std::getline(stream, line);) {
      if (line.rfind("warning: ", 0) == 0) continue;
      error = line, ++lines;
    }
    EXPECT_EQ(lines, 1) << what << "\n" << r.err;
    EXPECT_LE(error.size(), 1100u) << what << ": a line too long to read";
    EXPECT_EQ(error.rfind("radiosity: error: ", 0), 0u) << what << "\n" << r.err;
    EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << what << ": escape codes\n" << r.err;
    EXPECT_NE(r.err.find(names), std::string::npos) << what << ": must name " << names << "\n"
                                                    << r.err;
    EXPECT_NE(r.err.find(problem), std::string::npos) << what << ": must say " << problem << "\n"
                                                      << r.err;
    EXPECT_EQ(r.out, "") << what;
    EXPECT_TRUE(fs::is_empty(outputs)) << what << ": left files in " << outputs;
    std::string message = error;
    replace_all(message, (kData / "hostile").string(), "tests/data/hostile");
    replace_all(message, (kData / "bad").string(), "tests/data/bad");
    replace_all(message, (kRoot / "data").string(), "data");
    replace_all(message, (kRoot / "fuzz/regressions").string(), "fuzz/regressions");
    replace_all(message, inputs.string(), "(generated)");
    replace_all(message, outputs.string(), "out");
    replace_all(message, work.string(), "(test)");
    if (message.size() > 300) message = message.substr(0, 300) + " [...]";  // for the table
    replace_all(message, "|", "\\|");
    table += "| " + what + " | `" + message + "` |\n";
  };
  for (const auto& c : rad::test::hostile_inputs()) check(c.what, c.command, c.names, c.problem);
  for (const auto& c : rad::test::bad_scene_cases())
    check("scene: " + c.problem, "info {b}/" + c.file, c.element, c.problem);
  const size_t classes = rad::test::hostile_inputs().size() + rad::test::bad_scene_cases().size();
  EXPECT_GE(classes, 50u);
  if (const char* path = std::getenv("RAD_ROBUSTNESS_TABLE")) {
    std::ofstream(path) << table;
  }
}

}  // namespace
