// The pieces of an MPI run that a single process can check: the inputs' bytes recorded and
// replayed (scene/input_files.h), and a job of one (distributed/job.h). The job over several
// processes is checked by mpi_test.sh, under mpirun.
#include "distributed/job.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "scene/error.h"
#include "scene/input_files.h"
#include "scene/scene_loader.h"
#include "tests/scratch_dir.h"

namespace rad {
namespace {

TEST(InputFiles, SerializeRoundTripsBinaryBytes) {
  InputFiles files;
  files.add("a/scene.json", "{\"objects\": []}");
  files.add("a/mesh.stl", std::string("\0\1\2\xff binary", 11));
  files.add("empty", "");
  const InputFiles back = InputFiles::deserialize(files.serialize());
  ASSERT_NE(back.find("a/mesh.stl"), nullptr);
  EXPECT_EQ(*back.find("a/mesh.stl"), std::string("\0\1\2\xff binary", 11));
  EXPECT_EQ(*back.find("a/scene.json"), "{\"objects\": []}");
  EXPECT_EQ(*back.find("empty"), "");
  EXPECT_EQ(back.find("other"), nullptr);
  EXPECT_EQ(back.serialize(), files.serialize());
}

TEST(InputFiles, RefusesCutOrPaddedBundles) {
  InputFiles files;
  files.add("scene.json", "{}");
  const std::string bytes = files.serialize();
  for (size_t n = 0; n < bytes.size(); ++n)
    EXPECT_THROW(InputFiles::deserialize(bytes.substr(0, n)), Error) << n;
  EXPECT_THROW(InputFiles::deserialize(bytes + "x"), Error);
}

// The root records the scene and the mesh it names; another process loads the same scene from
// those bytes alone, with neither file on its disk.
TEST(InputFiles, ASceneLoadsFromTheRecordedBytesWithoutItsFiles) {
  const std::filesystem::path dir = test::scratch_dir("input_files");
  const std::filesystem::path scene_file = dir / "scene.json";
  {
    std::ofstream(dir / "quad.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    std::ofstream(scene_file) << R"({"materials": {"m": {"reflectance": [0.5, 0.5, 0.5]}},
      "objects": [{"mesh": "quad.obj", "material": "m"}]})";
  }
  InputFiles recorded;
  const Scene original = load_scene(scene_file, &recorded);
  ASSERT_NE(recorded.find(scene_file), nullptr);
  ASSERT_NE(recorded.find(dir / "quad.obj"), nullptr);
  std::filesystem::remove(dir / "quad.obj");
  std::filesystem::remove(scene_file);
  EXPECT_THROW(load_scene(scene_file), InputError);  // gone from the disk
  InputFiles sent = InputFiles::deserialize(recorded.serialize());
  const Scene copy = load_scene(scene_file, &sent);
  EXPECT_EQ(copy.fingerprint(), original.fingerprint());
  EXPECT_EQ(copy.polygons.size(), original.polygons.size());
}

TEST(JobOfOne, IsTheWorldOutsideMpirun) {
  const Job& job = Job::world();
  EXPECT_EQ(job.size(), 1);
  EXPECT_TRUE(job.is_root());
  EXPECT_FALSE(job.distributed());
  EXPECT_EQ(job.broadcast("bytes"), "bytes");
}

TEST(JobOfOne, AStepsExceptionPassesUnchanged) {
  // Alone, no agreement is needed: the error keeps its type and message (main prints it).
  try {
    Job::world().step([] { throw InputError("scene.json: objects[2]: bad"); });
    FAIL() << "no exception";
  } catch (const AgreedFailure&) {
    FAIL() << "wrapped";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "scene.json: objects[2]: bad");
  }
}

TEST(JobOfOne, RunsEveryBlockOnceInOrderWithoutPacking) {
  std::vector<size_t> computed, progress;
  BlockWork work;
  work.blocks = 5;
  work.compute = [&](size_t b) { computed.push_back(b); };
  work.pack = [](size_t) -> std::string { throw std::logic_error("packed"); };
  work.unpack = [](size_t, std::string_view) { throw std::logic_error("unpacked"); };
  work.progress = [&](size_t done) { progress.push_back(done); };
  Job::world().run_blocks(work);
  EXPECT_EQ(computed, (std::vector<size_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(progress, (std::vector<size_t>{1, 2, 3, 4, 5}));
}

}  // namespace
}  // namespace rad
