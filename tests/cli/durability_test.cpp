// Nothing lost, the same bytes every time, and no NaN (issue 16): outputs of killed processes
// leave the previous file whole; two processes writing one output leave one whole file; solve,
// probe and render give byte-identical files for 1, 2 and 4 threads and from run to run; and no
// NaN or infinity reaches an image, a CSV or a solution, at the Cornell box's corners and edges.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <thread>
#include <vector>

#include "formats/image_io.h"
#include "formats/solution_io.h"
#include "tests/cli/run_cli.h"

namespace {

using namespace rad::test::cli;
const fs::path kRoot = RAD_SOURCE_DIR;
const fs::path kData = RAD_TEST_DATA;
const std::string kCornell = quoted(kRoot / "data/cornell-box/scene.json");

/// Starts `radiosity ARGS` (split on spaces; no quoting needed for these paths) in the
/// background, output discarded.
pid_t start(const std::vector<std::string>& args) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::vector<char*> argv{const_cast<char*>(RADIOSITY_EXE)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1), ::dup2(null, 2);
    ::execv(RADIOSITY_EXE, argv.data());
    ::_exit(127);
  }
  return pid;
}

/// The files in `dir` that are temporaries of an AtomicFile (".name.tmpPID.ext").
int temporaries(const fs::path& dir) {
  int count = 0;
  for (const auto& e : fs::directory_iterator(dir))
    count += e.path().filename().string().find(".tmp") != std::string::npos;
  return count;
}

/// A large render to stop at moments of its run, over a small one's image: `full` is how long
/// it took whole, `after` what it wrote; the small image is back in place.
struct LargeRender {
  fs::path dir, image;
  std::vector<std::string> args;
  std::string before, after;
  double full = 0;

  LargeRender() : dir(scratch()), image(dir / "image.exr") {
    small();
    before = slurp(image);
    args = {"render",   (kRoot / "data/cornell-box/scene.json").string(),
            "--method", "albedo",
            "--width",  "2048",
            "--height", "2048",
            "-o",       image.string()};
    const auto t0 = std::chrono::steady_clock::now();
    int status = 0;
    ::waitpid(start(args), &status, 0);
    full = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    after = slurp(image);
    small();
  }
  /// The small image written again (over what a finished large render left).
  void small() const {
    ASSERT_EQ(
        run("render " + kCornell + " --method albedo --width 64 --height 64 -o " + quoted(image))
            .exit_code,
        0);
  }
  /// Starts the large render, waits `seconds`, sends `signal`; returns how it ended (waitpid).
  int stopped(double seconds, int signal) const {
    const pid_t pid = start(args);
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    ::kill(pid, signal);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return status;
  }
};

TEST(Durability, KilledWritesLeaveThePreviousFileWholeAndTheNextRunCleansUp) {
  // Large renders killed at times spread over their run: some before writing, some while the
  // temporary is being written, some after the rename.
  const LargeRender render;
  int with_temporary = 0;
  for (int k = 1; k <= 12; ++k) {
    render.stopped(render.full * k / 12.5, SIGKILL);
    with_temporary += temporaries(render.dir) > 0;
    const std::string now = slurp(render.image);
    EXPECT_TRUE(now == render.before || now == render.after) << "kill " << k << ": a partial image";
    if (now == render.after) render.small();  // finished before the kill
  }
  std::cout << with_temporary << " of 12 kills left a temporary behind\n";
  // The next successful run removes what killed processes left.
  render.small();
  EXPECT_EQ(temporaries(render.dir), 0);
  EXPECT_EQ(slurp(render.image), render.before);
}

TEST(Durability, InterruptedRunsLeaveNoTemporaryAndThePreviousFileWhole) {
  // Ctrl-C, a batch system's SIGTERM and a closed terminal's SIGHUP, at 8 times spread over a
  // render's run (some while it writes its temporary): the process dies of the signal, its
  // temporaries gone with it, and the image stays whole (the previous one, or the new one when
  // the signal came after the rename). (A solve writes only at its
  // end: the same code.)
  // A render that finishes before its signal (the machine busier while `full` was measured
  // than now: CI runs two tests at once) halves the later waits, so that most signals still
  // reach a running render.
  const LargeRender render;
  int interrupted = 0;
  double pace = 1;
  for (int k = 1; k <= 8; ++k) {
    const int signal = k % 3 == 0 ? SIGINT : k % 3 == 1 ? SIGTERM : SIGHUP;
    const double wait = render.full * pace * k / 8.5;
    const int status = render.stopped(wait, signal);
    EXPECT_EQ(temporaries(render.dir), 0) << "interrupt " << k << " left a temporary";
    if (WIFSIGNALED(status)) {
      EXPECT_EQ(WTERMSIG(status), signal) << "interrupt " << k;
      // Whole, the previous image or (a signal after the rename, while the process let go of
      // its 2048 x 2048 buffers: measured once in a fresh clone's run) the finished one; never
      // a part of either.
      const std::string now = slurp(render.image);
      EXPECT_TRUE(now == render.before || now == render.after)
          << "interrupt " << k << ": a partial image";
      if (now == render.after) render.small();
      ++interrupted;
    } else {  // finished before the signal
      ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
          << "interrupt " << k << " after " << wait << " s: status " << status;
      render.small();
      pace /= 2;
    }
  }
  EXPECT_GE(interrupted, 4) << "most signals reach the render while it runs (whole: " << render.full
                            << " s)";
}

TEST(Durability, TwoProcessesWritingOneOutputLeaveOneWholeFile) {
  const fs::path dir = scratch();
  const std::string out = (dir / "image.exr").string();
  const std::string scene = (kRoot / "data/cornell-box/scene.json").string();
  const pid_t a = start(
      {"render", scene, "--method", "albedo", "--width", "512", "--height", "512", "-o", out});
  const pid_t b = start(
      {"render", scene, "--method", "facing", "--width", "512", "--height", "512", "-o", out});
  int status = 0;
  ::waitpid(a, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  ::waitpid(b, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  const rad::Image image = rad::read_exr(out);
  EXPECT_EQ(image.width, 512);
  EXPECT_EQ(image.height, 512);
  EXPECT_EQ(temporaries(dir), 0);
}

TEST(Determinism, SolveProbeAndRenderAreByteIdenticalForAnyThreadCountAndRun) {
  const fs::path dir = scratch();
  const std::string points = quoted(kData / "points/cornell.csv");
  const auto outputs = [&](const std::string& tag, int threads) {
    const std::string j = " -j " + std::to_string(threads);
    const fs::path sub = dir / tag;
    fs::create_directories(sub);
    const std::string solution = quoted(sub / "solution.vtp");
    // Coarse (elements no smaller than 0.02 of the diagonal): identity, not accuracy, is tested.
    EXPECT_EQ(
        run("solve " + kCornell + " --patch-size 0.25 --min-element-size 0.02 -o " + solution + j)
            .exit_code,
        0);
    EXPECT_EQ(run("probe " + kCornell + " -s " + solution + " --points " + points +
                  " --method hemisphere --tolerance 0.05 -o " + quoted(sub / "probe.csv") + j)
                  .exit_code,
              0);
    for (const char* method :
         {"albedo", "facing", "patches", "hemisphere", "vertex", "montecarlo"}) {
      const std::string m = method;
      EXPECT_EQ(run("render " + kCornell + " -s " + solution + " --method " + m +
                    " --width 16 --height 16 --tolerance 0.05 --samples 16 -o " +
                    quoted(sub / (m + ".exr")) + j)
                    .exit_code,
                0)
          << m;
    }
    std::vector<std::pair<std::string, std::string>> files;
    for (const auto& e : fs::directory_iterator(sub)) {
      if (e.path().extension() == ".json") continue;  // render stats: seconds and threads
      files.emplace_back(e.path().filename().string(), slurp(e.path()));
    }
    std::sort(files.begin(), files.end());
    return files;
  };
  const auto reference = outputs("j1", 1);
  EXPECT_GE(reference.size(), 14u);  // solution, probe, 6 images with their previews
  for (const auto& [tag, threads] :
       std::vector<std::pair<std::string, int>>{{"j2", 2}, {"j4", 4}, {"j2-again", 2}}) {
    const auto other = outputs(tag, threads);
    ASSERT_EQ(other.size(), reference.size());
    for (size_t i = 0; i < other.size(); ++i) {
      EXPECT_EQ(other[i].first, reference[i].first);
      EXPECT_TRUE(other[i].second == reference[i].second)
          << other[i].first << " differs with " << threads << " threads (" << tag << ")";
    }
  }
}

TEST(Numbers, NoNaNOrInfinityReachesAnImageACsvOrASolution) {
  // The Cornell box's corners and edges (points/cornell.csv holds them) and every method.
  const fs::path dir = scratch();
  const std::string solution = quoted(dir / "solution.vtp");
  // Elements down to 0.01 of the diagonal along the contacts and edges: small ones are where
  // numbers go wrong, without the cost of the default's smallest (0.005) under the sanitizers.
  ASSERT_EQ(run("solve " + kCornell + " --patch-size 0.25 --min-element-size 0.01 -o " + solution)
                .exit_code,
            0);
  const rad::Solution s = rad::read_solution(dir / "solution.vtp");
  int checked = 0;
  for (const rad::Element& e : s.elements) {
    EXPECT_TRUE(e.radiosity.allFinite());
    for (const rad::Vec3& c : e.corners) EXPECT_TRUE(c.allFinite());
    ++checked;
  }
  for (const char* method : {"hemisphere", "vertex", "montecarlo"}) {
    const std::string m = method;
    ASSERT_EQ(run("probe " + kCornell + " -s " + solution + " --points " +
                  quoted(kData / "points/cornell.csv") + " --method " + m +
                  " --tolerance 0 --samples 64 -o " + quoted(dir / (m + ".csv")))
                  .exit_code,
              0);
    const std::string csv = slurp(dir / (m + ".csv"));
    for (const char* bad : {"nan", "NaN", "inf", "Inf"})
      EXPECT_EQ(csv.find(bad), std::string::npos) << m << ": " << bad << " in the CSV";
    ASSERT_EQ(
        run("render " + kCornell + " -s " + solution + " --method " + m +
            " --width 16 --height 16 --tolerance 0 --samples 16 -o " + quoted(dir / (m + ".exr")))
            .exit_code,
        0);
    const rad::Image image = rad::read_exr(dir / (m + ".exr"));
    for (const rad::Rgb& p : image.pixels) {
      EXPECT_TRUE(p.allFinite()) << m;
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
}

}  // namespace
