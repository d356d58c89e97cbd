// End-to-end tests of the `radiosity` executable: exit codes (0 ok, 1 runtime error, 2 usage),
// one-line messages naming file and element, and the files it writes.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <vtkCellData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <Eigen/Core>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "formats/image_io.h"
#include "formats/solution_io.h"
#include "tests/bad_scene_cases.h"
#include "tests/cli/run_cli.h"

namespace {

using namespace rad::test::cli;
const fs::path kRoot = RAD_SOURCE_DIR;
const fs::path kData = RAD_TEST_DATA;

TEST(Cli, EverySubcommandHasHelp) {
  for (const char* args : {"--help", "info --help", "solve --help", "probe --help", "render --help",
                           "sweep --help", "compare --help", "export --help"}) {
    const Result r = run(args);
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
    EXPECT_NE(r.out.find("Usage:"), std::string::npos) << args << "\n" << r.out;
  }
}

TEST(Cli, UsageErrorsExitTwo) {
  for (const char* args : {"", "info", "render scene.json", "info a.json --no-such-option",
                           "render x.json --method nope -o y.exr", "frobnicate", "compare a.exr",
                           "sweep x.json -s s.vtp -o d --tolerances 0,1.5",
                           "sweep x.json -s s.vtp -o d --methods nope",
                           "sweep x.json -s s.vtp -o d --samples 0", "export x.json -o d"}) {
    const Result r = run(args);
    EXPECT_EQ(r.exit_code, 2) << "'" << args << "'\n" << r.err;
    EXPECT_NE(r.err.find("--help"), std::string::npos) << r.err;
  }
}

TEST(Cli, MalformedScenesExitOneWithOneLineNamingFileAndElement) {
  for (const auto& c : rad::test::bad_scene_cases()) {
    const fs::path file = kData / "bad" / c.file;
    const Result r = run("info '" + file.string() + "'");
    EXPECT_EQ(r.exit_code, 1) << c.file << "\n" << r.err;
    EXPECT_EQ(r.out, "") << c.file;
    // One line, prefixed, naming the file, the element and the problem.
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.file << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("radiosity: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(file.string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.element), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.problem), std::string::npos) << r.err;
  }
}

TEST(Cli, InfoReportsTheCornellBox) {
  const Result r = run("info '" + (kRoot / "data/cornell-box/scene.json").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("polygons       20\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("emitters       1 polygon\n"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("warning: "), std::string::npos) << "the left wall's split is reported";

  const Result j = run("info --json '" + (kRoot / "data/cornell-box/scene.json").string() + "'");
  ASSERT_EQ(j.exit_code, 0) << j.err;
  const auto info = nlohmann::json::parse(j.out);
  EXPECT_EQ(info["polygons"], 20);
  EXPECT_EQ(info["emitters"], 1);
  EXPECT_EQ(info["materials"].size(), 4u);
  EXPECT_NEAR(info["emitted_power"][0].get<double>(), 130 * 105 * 53.4071, 1e-3);
  EXPECT_EQ(info["camera"]["width"], 512);
}

TEST(Cli, StrictTurnsAnOpenRefractingObjectIntoAnError) {
  // A glass box missing a face: a warning naming it; with --strict (before or after the
  // subcommand), an error, exit 1, one line.
  const std::string scene = quoted(kData / "open_glass.json");
  const Result warned = run("info " + scene);
  ASSERT_EQ(warned.exit_code, 0) << warned.err;
  EXPECT_NE(warned.err.find("warning: "), std::string::npos) << warned.err;
  EXPECT_NE(warned.err.find("\"open box\": refracting but not closed"), std::string::npos)
      << warned.err;
  std::string before = "--strict info ", after = "info ";
  before += scene;
  after += scene;
  after += " --strict";
  const std::vector<std::string> commands{before, after};
  for (const std::string& command : commands) {
    const Result r = run(command);
    EXPECT_EQ(r.exit_code, 1) << command << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("radiosity: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("refracting but not closed"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--strict"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

TEST(Cli, RenderAlbedoWritesExrAndPng) {
  const fs::path dir = scratch();
  const Result r =
      run("render '" + (kRoot / "data/cornell-box/scene.json").string() +
          "' --method albedo --width 40 --height 30 -o '" + (dir / "img.exr").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const rad::Image image = rad::read_exr(dir / "img.exr");
  EXPECT_EQ(image.width, 40);
  EXPECT_EQ(image.height, 30);
  EXPECT_TRUE(fs::exists(dir / "img.png"));
  EXPECT_GT(fs::file_size(dir / "img.png"), 100u);
  // Only the two outputs: no temporary files left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), {}), 2);
}

TEST(Cli, RenderWithoutCameraOrWithBadOutputExitsOne) {
  const fs::path dir = scratch();
  Result r = run("render '" + (kData / "meshes/square_obj.json").string() +
                 "' --method albedo -o '" + (dir / "x.exr").string() + "'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no \"camera\" block"), std::string::npos) << r.err;
  // An output whose folder cannot be created (a regular file is in the way).
  std::ofstream(dir / "file") << "x";
  r = run("render '" + (kRoot / "data/closed-cube/scene.json").string() +
          "' --method albedo --width 8 --height 8 -o '" + (dir / "file/x.exr").string() + "'");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("file/x.exr"), std::string::npos) << r.err;
  // export's picture needs the camera too: refused before anything is written; --no-png works.
  const std::string square = quoted(kData / "meshes/square_obj.json");
  r = run("solve " + square + " -o " + quoted(dir / "sq.vtp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run("export " + square + " -s " + quoted(dir / "sq.vtp") + " -o " + quoted(dir / "ex"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no \"camera\" block"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "ex"));
  r = run("export " + square + " -s " + quoted(dir / "sq.vtp") + " -o " + quoted(dir / "ex") +
          " --no-png");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "ex/octree.vtu"));
}

TEST(Cli, SolveThenRenderPatches) {
  const fs::path dir = scratch();
  const std::string scene = quoted(kRoot / "data/light-over-floor/scene.json");
  Result r = run("solve " + scene + " --patch-size 0.2 -o '" + (dir / "s.vtp").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("solve: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("energy: emitted"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("\r"), std::string::npos) << "no progress bar when stderr is not a terminal";
  r = run("render " + scene + " --method patches --solution '" + (dir / "s.vtp").string() +
          "' --width 48 --height 32 -o '" + (dir / "p.exr").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const rad::Image image = rad::read_exr(dir / "p.exr");
  ASSERT_EQ(image.width, 48);
  // The floor under the light is lit; some pixel is brighter than the ambient-only level.
  double brightest = 0;
  for (const auto& p : image.pixels) brightest = std::max(brightest, p.maxCoeff());
  EXPECT_GT(brightest, 0.05);
}

TEST(Cli, TheHierarchicalSolverSolvesOrSaysWhyItHandsOver) {
  // The hierarchical solver, the default, on a plain diffuse scene: links, sweeps and the time
  // of each step in the summary, a file the patches' render reads. On a scene with a glossy
  // ring: one line saying the progressive solver takes it, and a solve all the same.
  const fs::path dir = scratch();
  const std::string plain = quoted(kRoot / "data/light-over-floor/scene.json");
  Result r = run("solve " + plain + " --patch-size 0.2 -o '" + (dir / "h.vtp").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("sweeps over"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("not the links' approximations"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\ntime: linking "), std::string::npos) << r.err;
  r = run("render " + plain + " --method patches --solution '" + (dir / "h.vtp").string() +
          "' --width 16 --height 16 -o '" + (dir / "h.exr").string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::string lit = quoted(kRoot / "data/glossy-ring/scene.json");
  r = run("solve " + lit + " --solver hierarchical --patch-size 0.3 --refine-threshold 0 -o '" +
          (dir / "g.vtp").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("does not carry mirrors and glossy surfaces yet; solving progressively"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(" shots, unshot "), std::string::npos) << r.err;
  EXPECT_EQ(
      run("solve " + plain + " --solver nonsense -o '" + (dir / "x.vtp").string() + "'").exit_code,
      2);
}

TEST(Cli, ASolveInALogShowsItsProgressAndAMeshBeyondMemoryIsRefusedFirst) {
  const fs::path dir = scratch();
  const std::string cornell = quoted(kRoot / "data/cornell-box/scene.json");
  const std::string quick = " --patch-size 0.05 --element-levels 0 --refine-threshold 0";
  // stderr is a file here: whole lines, every --progress seconds, with the time so far.
  Result r = run("--progress 0.05 solve " + cornell + quick +
                 " --solver progressive --unshot 0.01 -o " + quoted(dir / "a.vtp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The progressive solver shoots; the hierarchical one (the default) links, then gathers.
  const auto progress_lines = [](const std::string& log, const std::string& stage,
                                 const std::string& detail) {
    int lines = 0, staged = 0;
    std::istringstream err(log);
    for (std::string line; std::getline(err, line);) {
      if (line.rfind("solve (", 0) != 0) continue;
      ++lines;
      const bool timed = line.ends_with(" s") || line.ends_with(" left");
      EXPECT_TRUE(timed) << "ends with the time so far, or the time left: " << line;
      if (line.rfind("solve (" + stage + "): ", 0) != 0) continue;
      ++staged;
      EXPECT_NE(line.find(detail), std::string::npos) << line;
    }
    EXPECT_GE(staged, 1) << log;
    return lines;
  };
  EXPECT_GE(progress_lines(r.err, "shooting", "% (target 1%), shot "), 3) << r.err;
  EXPECT_EQ(r.err.find("\r"), std::string::npos) << "no bar when stderr is not a terminal";
  r = run("--progress 0.05 solve " + cornell + quick + " --unshot 0.01 -o " +
          quoted(dir / "h.vtp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GE(progress_lines(r.err, "gathering", "% (target 1%), sweep "), 3) << r.err;
  // With refinement, the passes show theirs (seconds each, between the sweeps).
  r = run("--progress 0.05 solve " + cornell +
          " --patch-size 0.1 --element-levels 0 --unshot 0.01 -o " + quoted(dir / "r.vtp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  progress_lines(r.err, "refining", "elements tested, then the new ones linked");
  r = run("--progress 0 solve " + cornell + quick + " --unshot 0.01 -o " + quoted(dir / "b.vtp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("solve ("), std::string::npos) << r.err;
  // A mesh of billions of elements: refused at once, with what it would need.
  r = run("solve " + cornell + " --patch-size 1e-4 --element-levels 3 -o " + quoted(dir / "c.vtp"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("scene.json: meshed at --patch-size 0.0001 and --element-levels 3 it "
                       "makes at least "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(" elements (raise --patch-size or lower --element-levels), which need at "
                       "least "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(" GiB, more than half of this machine's "), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "c.vtp"));
}

TEST(Cli, RenderPatchesRefusesAMissingOrMismatchedSolution) {
  const fs::path dir = scratch();
  const std::string floor = quoted(kRoot / "data/light-over-floor/scene.json");
  Result r = run("render " + floor + " --method patches -o '" + (dir / "x.exr").string() + "'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("needs --solution"), std::string::npos) << r.err;
  r = run("solve " + floor + " --patch-size 0.3 --refine-threshold 0 -o '" +
          (dir / "floor.vtp").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run("render '" + (kRoot / "data/closed-cube/scene.json").string() +
          "' --method patches --solution '" + (dir / "floor.vtp").string() + "' -o '" +
          (dir / "x.exr").string() + "'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("solved for a different scene"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "x.exr"));
  // Bad solver settings are usage errors.
  r = run("solve " + floor + " --patch-size 0 -o '" + (dir / "y.vtp").string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
}

/// One CSV line's fields (no quoting in the project's CSVs).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> f;
  std::istringstream fields(line);
  for (std::string v; std::getline(fields, v, ',');) f.push_back(v);
  return f;
}

std::vector<std::vector<double>> parse_csv(const std::string& text, std::string* header) {
  std::istringstream in(text);
  std::getline(in, *header);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<double> row;
    std::istringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) row.push_back(std::stod(f));
    rows.push_back(row);
  }
  return rows;
}

TEST(Cli, ProbeWritesTheDocumentedCsvIndependentOfThreads) {
  const fs::path dir = scratch();
  const std::string args = "probe " + quoted(kRoot / "data/cornell-box/scene.json") + " --points " +
                           quoted(kData / "points/cornell.csv");
  const Result one = run(args + " -j 1");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const Result two = run(args + " -j 2 -o " + quoted(dir / "out.csv"));
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_EQ(one.out, slurp(dir / "out.csv")) << "byte-identical for any thread count";
  std::string header;
  const auto rows = parse_csv(one.out, &header);
  EXPECT_EQ(header, "x,y,z,nx,ny,nz,E_r,E_g,E_b,bound");
  ASSERT_EQ(rows.size(), 5u) << "comments, blank lines and the header are not points";
  for (const auto& r : rows) {
    ASSERT_EQ(r.size(), 10u);
    EXPECT_NEAR(Eigen::Vector3d(r[3], r[4], r[5]).norm(), 1.0, 1e-15) << "normals are normalized";
    for (int c = 6; c < 9; ++c) EXPECT_GE(r[c], 0);
    EXPECT_EQ(r[9], 0.0) << "exact results have a zero bound";
  }
  EXPECT_GT(rows[0][6], 0.1) << "the floor centre is lit";
  EXPECT_EQ(rows[3][4], 1.0) << "(0, 2, 0) normalized";
}

TEST(Cli, ProbeVertexMethodAgreesWithHemisphere) {
  const std::string args = "probe " + quoted(kRoot / "data/cornell-box/scene.json") + " --points " +
                           quoted(kRoot / "data/cornell-box/probe-points.csv");
  const Result hemisphere = run(args + " --method hemisphere");
  const Result vertex = run(args + " --method vertex");
  ASSERT_EQ(hemisphere.exit_code, 0) << hemisphere.err;
  ASSERT_EQ(vertex.exit_code, 0) << vertex.err;
  std::string header;
  const auto h = parse_csv(hemisphere.out, &header);
  const auto v = parse_csv(vertex.out, &header);
  ASSERT_EQ(h.size(), v.size());
  ASSERT_GT(h.size(), 0u);
  for (size_t i = 0; i < h.size(); ++i) {
    for (int c = 6; c < 9; ++c)
      EXPECT_NEAR(v[i][c], h[i][c], std::max(1e-9 * h[i][c], 1e-12)) << "row " << i;
  }
  EXPECT_NE(run(args + " --method montecarlo").exit_code, 0);
}

TEST(Cli, ProbePathTracesTheFurnaceWithStandardErrors) {
  // The closed cube (E = 1, rho = 0.5): H = 2 within 4 standard errors, in the extra columns,
  // the bound left empty; the path tracer takes no solution, and the same seeds give the same
  // file on any thread count.
  const fs::path dir = scratch();
  {
    std::ofstream points(dir / "cube.csv");
    points << "x,y,z,nx,ny,nz\n0.5,0.5,0,0,0,1\n0.2,0.8,0,0,0,1\n0.5,0,0.5,0,1,0\n";
  }
  const std::string args = "probe " + quoted(kRoot / "data/closed-cube/scene.json") + " --points " +
                           quoted(dir / "cube.csv") + " --method pathtrace --samples 4000";
  const Result r = run(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(run(args + " -j 1").out, r.out);
  std::istringstream in(r.out);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "x,y,z,nx,ny,nz,E_r,E_g,E_b,bound,se_r,se_g,se_b");
  int rows = 0;
  for (; std::getline(in, line); ++rows) {
    const std::vector<std::string> f = csv_fields(line);
    ASSERT_EQ(f.size(), 13u) << line;
    EXPECT_TRUE(f[9].empty()) << "nothing certified: " << line;
    const double e = std::stod(f[6]), se = std::stod(f[10]);
    EXPECT_NEAR(e, 2.0, 4 * se) << line;
    EXPECT_LT(se, 0.05) << line;
  }
  EXPECT_EQ(rows, 3);
  const Result refused = run(args + " --solution " + quoted(dir / "cube.csv"));
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("takes no --solution"), std::string::npos) << refused.err;
}

TEST(Cli, ProbeTracesToATargetErrorInBatches) {
  // --target-error: batches of --samples paths until every channel's standard error is at
  // most that fraction of the value; the first batch is the plain run's (a target it meets
  // gives the plain run's file), and the file is the same on any thread count. Asked of an
  // exact method, it is refused.
  const fs::path dir = scratch();
  {
    std::ofstream points(dir / "cube.csv");
    points << "x,y,z,nx,ny,nz\n0.5,0.5,0,0,0,1\n0.05,0.9,0,0,0,1\n";
  }
  const std::string args = "probe " + quoted(kRoot / "data/closed-cube/scene.json") + " --points " +
                           quoted(dir / "cube.csv") + " --method pathtrace --samples 200";
  const Result one = run(args), target = run(args + " --target-error 0.002");
  ASSERT_EQ(target.exit_code, 0) << target.err;
  EXPECT_EQ(run(args + " --target-error 0.002 -j 1").out, target.out);
  EXPECT_NE(target.out, one.out);
  // A target every first batch meets stops there: the plain run's file.
  EXPECT_EQ(run(args + " --target-error 1").out, one.out);
  std::istringstream in(target.out);
  std::string line;
  std::getline(in, line);
  int rows = 0;
  for (; std::getline(in, line); ++rows) {
    const std::vector<std::string> f = csv_fields(line);
    ASSERT_EQ(f.size(), 13u) << line;
    for (int c = 0; c < 3; ++c) {
      const double e = std::stod(f[6 + c]), se = std::stod(f[10 + c]);
      EXPECT_LE(se, 0.002 * e) << line;
      EXPECT_NEAR(e, 2.0, 4 * se) << line;
    }
  }
  EXPECT_EQ(rows, 2);
  const Result refused = run("probe " + quoted(kRoot / "data/closed-cube/scene.json") +
                             " --points " + quoted(dir / "cube.csv") + " --target-error 0.01");
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("--target-error is for --method pathtrace"), std::string::npos)
      << refused.err;
}

TEST(Cli, ProbeRejectsMalformedPointsNamingTheLine) {
  const std::string scene = quoted(kRoot / "data/cornell-box/scene.json");
  const std::pair<const char*, const char*> cases[] = {
      {"five_fields.csv", "five_fields.csv:2: expected 6 fields"},
      {"not_a_number.csv", "not_a_number.csv:2: field 3 'abc' is not a number"},
      {"zero_normal.csv", "zero_normal.csv:1: the normal (nx, ny, nz) is zero"},
      {"empty.csv", "empty.csv: no points"},
      {"missing.csv", "missing.csv: cannot open points file"},
  };
  for (const auto& [file, message] : cases) {
    const Result r = run("probe " + scene + " --points " + quoted(kData / "points" / file));
    EXPECT_EQ(r.exit_code, 1) << file;
    EXPECT_NE(r.err.find(message), std::string::npos) << file << ": " << r.err;
    EXPECT_EQ(r.out, "") << file;
  }
}

TEST(Cli, LocalPassRenderWritesImageStatsAndProbeFillsTheBound) {
  const fs::path dir = scratch();
  const std::string scene = quoted(kRoot / "data/light-over-floor/scene.json");
  Result r = run("solve " + scene + " --patch-size 0.2 -o " + quoted(dir / "s.vtp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run("render " + scene + " --method hemisphere --tolerance 0.2 --solution " +
          quoted(dir / "s.vtp") + " --width 16 --height 12 -o " + quoted(dir / "lp.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(rad::read_exr(dir / "lp.exr").width, 16);
  EXPECT_TRUE(fs::exists(dir / "lp.png"));
  const nlohmann::json stats = nlohmann::json::parse(slurp(dir / "lp.stats.json"));
  for (const char* key :
       {"seconds", "emitting_per_pixel", "emitting_fraction_mean", "projected_per_pixel", "bound",
        "faces", "octree_leaves", "pixels_gathered"}) {
    EXPECT_TRUE(stats.contains(key)) << key;
  }
  EXPECT_EQ(stats["tolerance"].get<double>(), 0.2);
  EXPECT_GT(stats["pixels_gathered"].get<int>(), 0);
  EXPECT_LE(stats["emitting_fraction_mean"].get<double>(), 1.0);
  // The exact methods need a solution.
  r = run("render " + scene + " --method vertex --width 8 --height 8 -o " + quoted(dir / "v.exr"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("needs --solution"), std::string::npos) << r.err;
  // probe with a solution: exact at tolerance 0 (bound 0), a bound >= 0 otherwise, within it.
  std::ofstream(dir / "p.csv") << "0,0,0,0,1,0\n0.3,0,0.2,0,1,0\n";
  const std::string probe = "probe " + scene + " --points " + quoted(dir / "p.csv") +
                            " --solution " + quoted(dir / "s.vtp");
  const Result exact = run(probe), bounded = run(probe + " --tolerance 0.3");
  ASSERT_EQ(exact.exit_code, 0) << exact.err;
  ASSERT_EQ(bounded.exit_code, 0) << bounded.err;
  std::string header;
  const auto e = parse_csv(exact.out, &header), b = parse_csv(bounded.out, &header);
  ASSERT_EQ(e.size(), 2u);
  ASSERT_EQ(b.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(e[i][9], 0.0);
    EXPECT_GE(b[i][9], 0.0);
    for (int c = 6; c < 9; ++c)
      EXPECT_LE(std::abs(b[i][c] - e[i][c]), b[i][9] * (1 + 1e-9) + 1e-12) << "row " << i;
  }
}

TEST(Cli, CompareReportsErrorsAndRefusesMissingOrMismatchedImages) {
  const fs::path dir = scratch();
  rad::Image a(4, 2), b(4, 2), small(2, 2);
  for (auto& p : a.pixels) p = rad::Rgb(1, 1, 1);
  for (auto& p : b.pixels) p = rad::Rgb(1, 1, 1);
  a.pixels[0] = rad::Rgb(1.5, 1, 1);  // one pixel 50% off: max 0.5, mean 0.5 / 8
  rad::write_exr(dir / "a.exr", a);
  rad::write_exr(dir / "b.exr", b);
  rad::write_exr(dir / "small.exr", small);
  Result r = run("compare " + quoted(dir / "a.exr") + " " + quoted(dir / "b.exr") + " -o " +
                 quoted(dir / "map.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("max relative error: 0.5\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mean relative error: 0.0625\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("pixels compared: 8 "), std::string::npos) << r.out;
  EXPECT_EQ(rad::read_exr(dir / "map.exr").at(0, 0).x(), 0.5f);
  EXPECT_TRUE(fs::exists(dir / "map.png"));

  r = run("compare " + quoted(dir / "missing.exr") + " " + quoted(dir / "b.exr"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("missing.exr"), std::string::npos) << r.err;
  r = run("compare " + quoted(dir / "small.exr") + " " + quoted(dir / "b.exr") + " -o " +
          quoted(dir / "m2.exr"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("small.exr: 2x2 pixels, but the reference"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "m2.exr"));
}

TEST(Cli, SweepAndExportWriteTheirFiles) {
  const fs::path dir = scratch();
  const std::string scene = quoted(kRoot / "data/light-over-floor/scene.json");
  Result r = run("solve " + scene + " --patch-size 0.25 -o " + quoted(dir / "s.vtp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run("sweep " + scene + " -s " + quoted(dir / "s.vtp") + " -o " + quoted(dir / "sweep") +
          " --width 8 --height 6 --tolerances 0,0.3 --methods hemisphere,montecarlo --samples 4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("sweep: hemisphere T=0.3: "), std::string::npos) << r.err;
  const std::string csv = slurp(dir / "sweep/results.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4) << csv;  // header + 3 rows
  for (const char* file :
       {"reference.exr", "error_vs_tolerance.png", "time_vs_tolerance.png", "error_vs_time.png",
        "images/hemisphere_T0.3.exr", "error_maps/montecarlo_N4.png"}) {
    EXPECT_TRUE(fs::exists(dir / "sweep" / file)) << file;
  }

  // Again with that reference from the file: the tolerance-0 row is rendered and agrees with it
  // to float precision, and no pixel leaves its bound.
  r = run("sweep " + scene + " -s " + quoted(dir / "s.vtp") + " -o " + quoted(dir / "sweep2") +
          " --width 8 --height 6 --tolerances 0,0.3 --methods hemisphere --reference " +
          quoted(dir / "sweep/reference.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream csv2(slurp(dir / "sweep2/results.csv"));
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(csv2, line);) rows.push_back(csv_fields(line));
  ASSERT_EQ(rows.size(), 3u);  // header + T = 0 + T = 0.3
  EXPECT_EQ(rows[0][6], "error_max");
  EXPECT_EQ(rows[0][9], "bound_violations");
  EXPECT_LE(std::stod(rows[1][6]), 1e-6);  // T = 0 against the float reference
  EXPECT_EQ(rows[1][9], "0");
  EXPECT_EQ(rows[2][9], "0");
  r = run("sweep " + scene + " -s " + quoted(dir / "s.vtp") + " -o " + quoted(dir / "sweep3") +
          " --width 9 --height 6 --reference " + quoted(dir / "sweep/reference.exr"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("reference.exr: 8x6 pixels, but the sweep renders 9x6"), std::string::npos)
      << r.err;

  r = run("render " + scene + " --solution " + quoted(dir / "s.vtp") + " --width 8 --height 6 -o " +
          quoted(dir / "lp.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run("export " + scene + " -s " + quoted(dir / "s.vtp") + " -o " + quoted(dir / "export") +
          " --stats " + quoted(dir / "lp.stats.json") + " --width 64 --height 48");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* file : {"patch_mesh.vtp", "octree.vtu", "pixel_stats.vti", "patch_mesh.png"}) {
    EXPECT_TRUE(fs::exists(dir / "export" / file)) << file;
  }
  // Read back with VTK's readers: the render's 8 x 6 pixels with their statistics, the mesh's
  // cells as the solution's elements, the octree's hexahedra with their arrays.
  vtkNew<vtkXMLImageDataReader> pixels;
  pixels->SetFileName((dir / "export/pixel_stats.vti").c_str());
  pixels->Update();
  int dims[3];
  pixels->GetOutput()->GetDimensions(dims);
  EXPECT_EQ(dims[0], 8);
  EXPECT_EQ(dims[1], 6);
  for (const char* name :
       {"projected", "emitting", "surface", "bound", "relative_bound", "interpolated"}) {
    EXPECT_NE(pixels->GetOutput()->GetPointData()->GetArray(name), nullptr) << name;
  }
  vtkNew<vtkXMLPolyDataReader> mesh;
  mesh->SetFileName((dir / "export/patch_mesh.vtp").c_str());
  mesh->Update();
  EXPECT_EQ(mesh->GetOutput()->GetNumberOfCells(),
            static_cast<vtkIdType>(rad::read_solution(dir / "s.vtp").elements.size()));
  vtkNew<vtkXMLUnstructuredGridReader> octree;
  octree->SetFileName((dir / "export/octree.vtu").c_str());
  octree->Update();
  EXPECT_GT(octree->GetOutput()->GetNumberOfCells(), 0);
  for (const char* name : {"bmax", "patch_count", "energy", "level", "leaf"}) {
    EXPECT_NE(octree->GetOutput()->GetCellData()->GetArray(name), nullptr) << name;
  }
  // A stats file that is not one names itself, and nothing is written.
  std::ofstream(dir / "bad.json") << "{\"seconds\": 1}";
  r = run("export " + scene + " -s " + quoted(dir / "s.vtp") + " -o " + quoted(dir / "export2") +
          " --stats " + quoted(dir / "bad.json"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad.json: no \"pixels_file\""), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "export2"));
}

}  // namespace
