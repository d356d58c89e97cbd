// A user's own scene from the command line (issue 39): an OBJ+MTL alone solves and renders
// with its materials and a camera from its bounds; a room whose fronts face out warns, fails
// under --strict and is turned by --flip-normals; the preview's exposure comes from the image.
// The materials themselves are checked in tests/scene/mtl_test.cpp.
#include <string>

#include "formats/image_io.h"
#include "tests/cli/run_cli.h"

namespace {

using namespace rad::test::cli;
const fs::path kRoom = fs::path(RAD_SOURCE_DIR) / "tests/data/obj-room";
/// A coarse solve: these tests need a solution file, not a good one.
const std::string kCoarse = " --element-levels 0 --refine-passes 0 --max-shots 20";

TEST(UserScene, AnObjAloneSolvesAndRendersWithItsMaterials) {
  const fs::path dir = scratch();
  const std::string room = quoted(kRoom / "room.obj");
  Result r = run("info " + room);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // no warning: every face has its material
  EXPECT_NE(r.out.find("emitters       1 polygon"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Lamp         reflectance (0, 0, 0)  emission (31.4159"), std::string::npos)
      << r.out;
  ASSERT_EQ(run("solve " + room + kCoarse + " -o " + quoted(dir / "s.vtp")).exit_code, 0);
  r = run("render " + room + " --method hemisphere --solution " + quoted(dir / "s.vtp") +
          " --width 12 --height 12 -o " + quoted(dir / "r.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The exposure chosen from the image, and said; a given one is kept.
  EXPECT_NE(r.err.find(", from the image)"), std::string::npos) << r.err;
  const rad::Image image = rad::read_exr(dir / "r.exr");
  for (const rad::Rgb& pixel : image.pixels) EXPECT_GT(pixel.minCoeff(), 0);  // lit everywhere
  r = run("render " + room + " --method facing --width 12 --height 12 --exposure -1 -o " +
          quoted(dir / "f.exr"));
  EXPECT_NE(r.err.find("(exposure -1)"), std::string::npos) << r.err;
}

TEST(UserScene, ARoomFacingOutWarnsFailsUnderStrictAndFlipsBack) {
  const std::string outward = quoted(kRoom / "room-outward.obj");
  Result r = run("info " + outward);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.err.find("warning: "), std::string::npos);
  EXPECT_NE(r.err.find("no polygon faces a light"), std::string::npos) << r.err;
  r = run("--strict info " + outward);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--flip-normals turns every polygon (--strict"), std::string::npos) << r.err;
  // Before or after the command, the flag turns the room to face in: no warning.
  for (const std::string& args :
       {"--flip-normals info " + outward, "--strict info " + outward + " --flip-normals"}) {
    r = run(args);
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
    EXPECT_EQ(r.err, "") << args;
  }
}

}  // namespace
