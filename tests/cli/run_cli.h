#pragma once
// Running the `radiosity` executable from a test: its exit code, stdout and stderr (shared by
// the CLI suites). RADIOSITY_EXE is the executable's path (tests/CMakeLists.txt).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rad::test::cli {

namespace fs = std::filesystem;

struct Result {
  int exit_code = -1;  ///< -1: killed by a signal (a crash)
  std::string out, err;
};

inline std::string slurp(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// An empty folder of the current test's own.
inline fs::path scratch() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() / (std::string("rad_cli_test_") + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// A path in single quotes for the shell.
inline std::string quoted(const fs::path& path) {
  std::string q(1, '\'');
  q.append(path.string()).push_back('\'');
  return q;
}

/// Runs `radiosity ARGS` with stdout and stderr captured separately, stdin empty, and at most
/// `timeout_seconds` (a hang exits 124, from coreutils' timeout).
inline Result run(const std::string& args, int timeout_seconds = 600) {
  const fs::path dir = fs::temp_directory_path() / "rad_cli_capture";
  fs::create_directories(dir);
  const std::string tag = std::to_string(::getpid());
  const fs::path out = dir / (tag + ".out"), err = dir / (tag + ".err");
  const std::string command = "timeout " + std::to_string(timeout_seconds) + " '" + RADIOSITY_EXE +
                              "' " + args + " >'" + out.string() + "' 2>'" + err.string() +
                              "' </dev/null";
  const int status = std::system(command.c_str());
  Result r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

}  // namespace rad::test::cli
