// Nothing a user wrote is lost (issue 39): an output is never an input nor another output, a
// symlink is followed and kept, a device, a FIFO and stdout are written through, a failed write
// to stdout exits 1, a render's files are replaced as a whole or not at all, temporaries are
// unique and a stale one of any name breaks nothing; and a FIFO given as an input is refused at
// once instead of blocking. Each case was reproduced on the code before the fix.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <string>

#include "formats/image_io.h"
#include "tests/cli/run_cli.h"

namespace {

using namespace rad::test::cli;
const fs::path kRoot = RAD_SOURCE_DIR;
const std::string kCornell = quoted(kRoot / "data/cornell-box/scene.json");
const std::string kPoints = quoted(kRoot / "data/cornell-box/probe-points.csv");
/// A coarse solve (a second, where the default takes fifteen; ten times that under the
/// sanitizers): these tests need a solution file, not a good one.
const std::string kCoarse = " --element-levels 0 --refine-passes 0 --max-shots 20";
const std::string kAlbedo = "render " + kCornell + " --method albedo --width 16 --height 12";

/// The exit status of `radiosity ARGS` run by the shell with `redirect` (e.g. "> /dev/full").
int status_of(const std::string& args, const std::string& redirect) {
  const std::string command =
      std::string("timeout 120 '") + RADIOSITY_EXE + "' " + args + " " + redirect;
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// Exit 1 with one error line (the scene's warnings aside), and it says `what`.
void expect_one_line_error(const Result& r, const std::string& what) {
  EXPECT_EQ(r.exit_code, 1) << r.err;
  size_t errors = 0;
  std::istringstream lines(r.err);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("warning: ", 0) == 0) continue;
    ++errors;
    EXPECT_NE(line.find(what), std::string::npos) << r.err;
  }
  EXPECT_EQ(errors, 1u) << r.err;
}

TEST(OutputSafety, AnImageNamedLikeItsPreviewOrStatsIsRefusedBeforeAnyWork) {
  const fs::path dir = scratch();
  // -o out.png: the EXR and then the PNG preview would go to one file.
  Result r = run(kAlbedo + " -o " + quoted(dir / "out.png"));
  expect_one_line_error(r, "is also the image (-o)");
  EXPECT_FALSE(fs::exists(dir / "out.png"));
  r = run(kAlbedo + " -o " + quoted(dir / "a.exr") + " --preview " + quoted(dir / "a.exr"));
  expect_one_line_error(r, "is also the image (-o)");
  // The same file by another name (a symlink to it) is the same file.
  ASSERT_EQ(run(kAlbedo + " -o " + quoted(dir / "b.exr") + " --no-preview").exit_code, 0);
  fs::create_symlink(dir / "b.exr", dir / "b-link.png");
  r = run(kAlbedo + " -o " + quoted(dir / "b.exr") + " --preview " + quoted(dir / "b-link.png"));
  expect_one_line_error(r, "is also the image (-o)");
}

TEST(OutputSafety, AnOutputThatIsAnInputIsRefusedAndTheInputKept) {
  const fs::path dir = scratch();
  const fs::path scene = dir / "s.json";
  fs::copy_file(kRoot / "data/cornell-box/scene.json", scene);
  const std::string before = slurp(scene);
  expect_one_line_error(run("solve " + quoted(scene) + " -o " + quoted(scene)), "is the input");
  EXPECT_EQ(slurp(scene), before);
  // By a hard link: another name, the same inode.
  fs::create_hard_link(scene, dir / "hard.vtp");
  expect_one_line_error(run("solve " + quoted(scene) + " -o " + quoted(dir / "hard.vtp")),
                        "is the input");
  EXPECT_EQ(slurp(scene), before);
  // A render over its own solution.
  const fs::path solution = dir / "s.vtp";
  ASSERT_EQ(run("solve " + quoted(scene) + kCoarse + " -o " + quoted(solution)).exit_code, 0);
  const std::string solved = slurp(solution);
  expect_one_line_error(run("render " + quoted(scene) + " -s " + quoted(solution) +
                            " --width 8 --height 6 -o " + quoted(solution)),
                        "is the input");
  EXPECT_EQ(slurp(solution), solved);
  // A probe over its points file.
  const fs::path points = dir / "p.csv";
  fs::copy_file(kRoot / "data/cornell-box/probe-points.csv", points);
  expect_one_line_error(
      run("probe " + quoted(scene) + " -p " + quoted(points) + " -o " + quoted(points)),
      "is the input");
}

TEST(OutputSafety, ASymlinkIsFollowedAndKept) {
  const fs::path dir = scratch();
  fs::create_directories(dir / "real");
  ASSERT_EQ(run(kAlbedo + " --no-preview -o " + quoted(dir / "real/image.exr")).exit_code, 0);
  fs::create_symlink("real/image.exr", dir / "link.exr");
  const std::string old = slurp(dir / "real/image.exr");
  const std::string wider = "render " + kCornell + " --method albedo --width 20 --height 12";
  ASSERT_EQ(run(wider + " --no-preview -o " + quoted(dir / "link.exr")).exit_code, 0);
  EXPECT_TRUE(fs::is_symlink(dir / "link.exr"));
  EXPECT_NE(slurp(dir / "real/image.exr"), old);  // the target got the new image
  // A dangling link: the file it names is created.
  fs::create_symlink("real/new.exr", dir / "dangling.exr");
  ASSERT_EQ(run(kAlbedo + " --no-preview -o " + quoted(dir / "dangling.exr")).exit_code, 0);
  EXPECT_TRUE(fs::is_symlink(dir / "dangling.exr"));
  EXPECT_TRUE(fs::is_regular_file(dir / "real/new.exr"));
}

TEST(OutputSafety, DevicesFifosAndStdoutAreWrittenThrough) {
  const fs::path dir = scratch();
  // /dev/null stays a device (as root, a rename would have replaced it with a file).
  ASSERT_EQ(run(kAlbedo + " -o /dev/null --preview /dev/null").exit_code, 0);
  struct stat st {};
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  // The probe's CSV through /dev/stdout and through "-".
  for (const char* target : {"/dev/stdout", "-"}) {
    const Result r = run("probe " + kCornell + " -p " + kPoints + " -o " + target);
    EXPECT_EQ(r.exit_code, 0) << target << r.err;
    EXPECT_EQ(r.out.rfind("x,y,z,nx,ny,nz,E_r,E_g,E_b,bound", 0), 0u) << target << r.out;
  }
  // A FIFO: the bytes arrive at the reader, the FIFO stays one.
  const fs::path fifo = dir / "pipe.csv";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string read_back = (dir / "read.csv").string();
  const std::string reader = "cat " + quoted(fifo) + " > '" + read_back + "' &";
  ASSERT_EQ(std::system(reader.c_str()), 0);
  EXPECT_EQ(run("probe " + kCornell + " -p " + kPoints + " -o " + quoted(fifo)).exit_code, 0);
  for (int i = 0; i < 100 && slurp(read_back).empty(); ++i) ::usleep(50000);
  EXPECT_EQ(slurp(read_back).rfind("x,y,z", 0), 0u);
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
}

TEST(OutputSafety, AFailedWriteToStdoutExitsOne) {
  EXPECT_EQ(status_of("probe " + kCornell + " -p " + kPoints, "> /dev/full 2>/dev/null"), 1);
  EXPECT_EQ(status_of("info " + kCornell, "> /dev/full 2>/dev/null"), 1);
  EXPECT_EQ(status_of("probe " + kCornell + " -p " + kPoints + " -o -", "> /dev/full 2>/dev/null"),
            1);
  EXPECT_EQ(status_of("info " + kCornell, "> /dev/null"), 0);
}

TEST(OutputSafety, ARenderReplacesItsFilesAsAWholeOrNotAtAll) {
  const fs::path dir = scratch();
  const fs::path solution = dir / "s.vtp";
  ASSERT_EQ(run("solve " + kCornell + kCoarse + " -o " + quoted(solution)).exit_code, 0);
  const std::string render = "render " + kCornell + " -s " + quoted(solution) +
                             " --method hemisphere --tolerance 0.5 --width 8 --height 6 -o " +
                             quoted(dir / "r.exr");
  ASSERT_EQ(run(render).exit_code, 0);
  const std::string exr = slurp(dir / "r.exr"), png = slurp(dir / "r.png");
  // The stats cannot be written (their folder is a file): the image and preview stay as they
  // were, where they used to be replaced before the failure.
  std::ofstream(dir / "blocker") << "a file, not a folder";
  const Result r = run(render + " --exposure 3 --stats " + quoted(dir / "blocker/r.stats.json"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(slurp(dir / "r.exr"), exr);
  EXPECT_EQ(slurp(dir / "r.png"), png);
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST(OutputSafety, AStaleTemporaryOfAnyNameBreaksNothing) {
  const fs::path dir = scratch();
  std::ofstream(dir / ".r.tmp99999999999999999999.exr") << "stale";
  std::ofstream(dir / ".r.tmp.AbCdEf.exr") << "stale, in today's form";
  const Result r = run(kAlbedo + " --no-preview -o " + quoted(dir / "r.exr"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(dir / "r.exr"));
  EXPECT_FALSE(fs::exists(dir / ".r.tmp.AbCdEf.exr"));  // nobody holds it: cleaned up
}

TEST(OutputSafety, AFifoOrAFolderGivenAsAnInputIsRefusedAtOnce) {
  const fs::path dir = scratch();
  const fs::path fifo = dir / "scene.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // Opening a FIFO for reading waits for a writer: the command used to hang here.
  expect_one_line_error(run("info " + quoted(fifo), 30), "a FIFO, not a regular file");
  const fs::path points = dir / "points.csv";
  ASSERT_EQ(::mkfifo(points.c_str(), 0600), 0);
  expect_one_line_error(run("probe " + kCornell + " -p " + quoted(points), 30),
                        "a FIFO, not a regular file");
  const fs::path solution = dir / "s.vtp";
  ASSERT_EQ(::mkfifo(solution.c_str(), 0600), 0);
  expect_one_line_error(
      run(kAlbedo.substr(0, kAlbedo.find(" --method")) + " -s " + quoted(solution) +
              " --width 8 --height 6 -o " + quoted(dir / "x.exr"),
          30),
      "a FIFO, not a regular file");
  fs::create_directories(dir / "folder.json");
  expect_one_line_error(run("info " + quoted(dir / "folder.json"), 30), "a folder, not a regular");
}

TEST(HonestOutputs, NanOptionsAreRefusedAndTheStatsSayTheThreadsUsed) {
  const fs::path dir = scratch();
  for (const char* option :
       {"--tolerance nan", "--exposure nan", "--tolerance inf", "--exposure -inf"}) {
    const Result r =
        run("render " + kCornell + " --method albedo " + option + " -o " + quoted(dir / "x.exr"));
    EXPECT_EQ(r.exit_code, 2) << option << r.err;
    // inf is out of every range already; NaN passed them all.
    if (std::string(option).find("nan") != std::string::npos) {
      EXPECT_NE(r.err.find("not a finite number"), std::string::npos) << option << r.err;
    }
  }
  EXPECT_EQ(run("compare " + quoted(dir / "a.exr") + " " + quoted(dir / "b.exr") + " --max nan")
                .exit_code,
            2);
  EXPECT_EQ(run("compare " + quoted(dir / "a.exr") + " " + quoted(dir / "b.exr") + " --floor nan")
                .exit_code,
            2);
  const fs::path solution = dir / "s.vtp";
  EXPECT_EQ(run("sweep " + kCornell + " -s " + quoted(solution) + " -o " + quoted(dir / "sw") +
                " --tolerances 0.1,nan")
                .exit_code,
            2);
  ASSERT_EQ(run("solve " + kCornell + kCoarse + " -o " + quoted(solution)).exit_code, 0);
  const Result r = run("render " + kCornell + " -s " + quoted(solution) +
                       " --tolerance 0.5 --width 8 --height 6 -j 1 -o " + quoted(dir / "r.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(slurp(dir / "r.stats.json").find("\"threads\": 1,"), std::string::npos);
}

TEST(HonestOutputs, CompareRefusesWhatItCannotCompare) {
  const fs::path dir = scratch();
  rad::Image grey(4, 3), black(4, 3), with_nan(4, 3);
  for (rad::Rgb& p : grey.pixels) p = rad::Rgb::Constant(0.5);
  with_nan.pixels = grey.pixels;
  with_nan.pixels[5] = rad::Rgb(0.5, std::nan(""), 0.5);
  rad::write_exr(dir / "grey.exr", grey);
  rad::write_exr(dir / "black.exr", black);
  rad::write_exr(dir / "nan.exr", with_nan);
  rad::write_exr_channels(dir / "y.exr", {4, 3, {{"Y", std::vector<float>(12, 0.5f)}}});
  const std::string grey_exr = quoted(dir / "grey.exr");
  EXPECT_EQ(run("compare " + grey_exr + " " + grey_exr).exit_code, 0);
  // These used to report "pixels compared: 0" or pass NaN unchecked, with exit 0.
  expect_one_line_error(run("compare " + grey_exr + " " + quoted(dir / "y.exr")),
                        "no R channel: not an RGB image (its channels: Y)");
  expect_one_line_error(run("compare " + grey_exr + " " + quoted(dir / "black.exr")),
                        "no pixel to compare");
  expect_one_line_error(run("compare " + quoted(dir / "nan.exr") + " " + grey_exr),
                        "pixel (1, 1) is not a finite number");
  // -o map.png: the error map and then its heat map went to one file.
  expect_one_line_error(
      run("compare " + grey_exr + " " + grey_exr + " -o " + quoted(dir / "map.png")),
      "is also the error map (-o)");
  EXPECT_FALSE(fs::exists(dir / "map.png"));
}

TEST(HonestOutputs, PointsRowsAreNeverDroppedAndHugeNormalsStayNormals) {
  const fs::path dir = scratch();
  std::ofstream(dir / "seven.csv") << "0.1,0.2,0.3,0,0,1,9\n0.1,0.2,0.3,0,0,1\n";
  expect_one_line_error(run("probe " + kCornell + " -p " + quoted(dir / "seven.csv")),
                        "seven.csv:1: expected 6 fields x,y,z,nx,ny,nz, got 7");
  std::ofstream(dir / "five.csv") << "0.1,0.2,0.3,0,0\n";
  expect_one_line_error(run("probe " + kCornell + " -p " + quoted(dir / "five.csv")),
                        "five.csv:1: expected 6 fields");
  std::ofstream(dir / "huge.csv") << "x,y,z,nx,ny,nz\n278,1,280,1e300,1e300,1e300\n"
                                  << "278,1,280,0,1e-300,0\n";
  const Result r = run("probe " + kCornell + " -p " + quoted(dir / "huge.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream rows(r.out);
  std::string header, first, second;
  std::getline(rows, header), std::getline(rows, first), std::getline(rows, second);
  EXPECT_EQ(first.rfind("278,1,280,0.5773502691896258,0.5773502691896258,0.5773502691896258,", 0),
            0u)
      << first;
  EXPECT_EQ(second.rfind("278,1,280,0,1,0,", 0), 0u) << second;
}

TEST(HonestOutputs, LightsWhosePowerOverflowsAreRefusedBeforeSolving) {
  const fs::path dir = scratch();
  const auto scene = [&](const std::string& name, const std::string& emission,
                         const std::string& lights) {
    std::ofstream(dir / name) << R"({"materials": {"floor": {"reflectance": 0.5},
      "lamp": {"reflectance": 0, "emission": )"
                              << emission << R"(}},
      "objects": [{"material": "floor", "polygons": [[[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]]]},
                  {"name": "lamp", "material": "lamp",
                   "polygons": [[[-0.5, 1, -0.5], [0.5, 1, -0.5], [0.5, 1, 0.5], [-0.5, 1, 0.5]]]}])"
                              << lights << "}";
    return quoted(dir / name);
  };
  EXPECT_EQ(run("info " + scene("ok.json", "1e90", "")).exit_code, 0);
  // Each used to solve with exit 0: infinite pixels, a file render refuses, "0% unshot".
  expect_one_line_error(
      run("solve " + scene("e300.json", "1e300", "") + " -o " + quoted(dir / "s.vtp")),
      "objects[1] \"lamp\" polygon 0: emits more than 1e+100 W");
  expect_one_line_error(
      run("solve " + scene("e308.json", "1.7e308", "") + " -o " + quoted(dir / "s.vtp")),
      "emits more than 1e+100 W");
  expect_one_line_error(
      run("solve " +
          scene("light.json", "1",
                R"(, "lights": [{"position": [0, 0.5, 0], "intensity": 1e308}])") +
          " -o " + quoted(dir / "s.vtp")),
      "lights[0]: emits more than 1e+100 W");
  EXPECT_FALSE(fs::exists(dir / "s.vtp"));
}

TEST(HonestOutputs, MessagesKeepTheProblemWhateverTheNamesHold) {
  const fs::path dir = scratch();
  const auto scene = [&](const std::string& file, const std::string& name,
                         const std::string& material, const std::string& corner) {
    std::ofstream(dir / file) << R"({"materials": {")" << name << R"(": {"reflectance": 0.5}},
      "objects": [{"name": ")" << name
                              << R"(", "material": ")" << material
                              << R"(", "polygons": [[[0, 0, 0], [1, 0, 0], )" << corner
                              << R"(, [0, 1, 0]]]}]})";
    return quoted(dir / file);
  };
  // A NUL in a name: what() is a C string, and ended there, before the problem.
  Result r = run("info " + scene("nul.json", "a\\u0000b", "x", "[1, 1, 0]"));
  expect_one_line_error(r, "unknown material \"x\"");
  EXPECT_NE(r.err.find("a\\0b"), std::string::npos) << r.err;
  // A name of a megabyte: the line is cut in its middle, the problem at its end kept.
  r = run("info " + scene("long.json", std::string(1 << 20, 'n'), "x", "[1, 1, 0]"));
  expect_one_line_error(r, "unknown material \"x\"");
  EXPECT_LT(r.err.size(), 1100u);
  // Coordinates of 1e200: lengths overflow; it said "has 1 distinct vertices".
  expect_one_line_error(run("info " + scene("far.json", "m", "m", "[1e200, -1e200, 0]")),
                        "vertex 2 (1e+200, -1e+200, 0) lies beyond +-1e100");
  // An escape sequence in a name does not reach the terminal.
  r = run("info " + scene("esc.json", "red\\u001b[31m", "red\\u001b[31m", "[1, 1, 0]"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos);
}

}  // namespace
