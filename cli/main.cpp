// radiosity: a radiosity system with an exact local pass (see README.md).
//
// Exit codes: 0 success; 1 runtime error (bad input file, I/O), with one line on stderr naming
// the problem; 2 usage error (unknown option, missing argument).
//
// Under mpirun (docs/cluster.md) every process runs main: render, probe and sweep split their
// work over all of them (distributed/job.h); the other commands run on the root alone. Only the
// root prints and writes; the others' stdout and stderr are muted.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>
#include <string>

#include "cli/commands.h"
#include "cli/common.h"
#include "distributed/job.h"
#include "scene/error.h"

namespace {

/// One line, whatever a message holds: line breaks, escape codes and other control characters
/// (a library's coloured log, a file name with a newline) become spaces.
std::string one_line(const std::string& message) {
  // A message quotes what it found in a file, which may be one 2 GB "word" (a name of a
  // megabyte): a line stays readable at 1000 characters, cut in the middle, so that its start
  // (the file) and its end (the problem) both show.
  constexpr size_t kHead = 400, kTail = 600;
  std::string out;
  for (const char c : message) {
    const bool control = rad::cli::is_control_byte(c);
    if (control && (out.empty() || out.back() == ' ')) continue;
    out += control ? ' ' : c;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  if (out.size() > kHead + kTail)
    out = out.substr(0, kHead) + " [...] " + out.substr(out.size() - kTail);
  return out;
}

/// Runs the chosen command; returns the exit status, having printed the one line of a failure.
int run_command(const rad::Job& job, const rad::cli::Run& run, bool distributed) {
  try {
    if (distributed) {
      // One last agreement: a failure on one process (an output the root could not write,
      // say) ends every process with status 1 and the root's one line.
      job.step(run);
    } else {
      run();
    }
  } catch (const rad::AgreedFailure& e) {
    if (!e.quiet()) std::cerr << "radiosity: error: " << one_line(e.what()) << "\n";
    return 1;
  } catch (const rad::Error& e) {
    std::cerr << "radiosity: error: " << one_line(e.what()) << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "radiosity: error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "radiosity: unexpected error: " << one_line(e.what()) << "\n";
    return 1;
  }
  return 0;
}

/// A stream buffer that drops what is written to it: the non-root processes' stdout and stderr.
class Muted : public std::streambuf {
 protected:
  int overflow(int c) override { return traits_type::not_eof(c); }
};

/// Flushes stdout and checks that all of it was written (a full disk, a closed pipe): what a
/// command printed there is its result. Returns the status to exit with.
int checked_stdout(int status) {
  errno = 0;
  std::cout.flush();
  const bool ok = std::fflush(stdout) == 0 && !std::ferror(stdout) && std::cout.good();
  const int error = errno;
  if (ok) return status;
  std::cerr << "radiosity: error: cannot write to stdout"
            << (error != 0 ? std::string(": ") + std::strerror(error) : std::string()) << "\n";
  return 1;
}

int run_main(const rad::Job& job, int argc, char** argv) {
  static Muted muted;  // outlives main: the streams flush at exit
  if (!job.is_root()) {
    std::cout.rdbuf(&muted);
    std::cerr.rdbuf(&muted);
  }
  CLI::App app{
      "radiosity: a radiosity solver with an exact, error-bounded local pass.\n"
      "Results go to files or stdout; progress and messages to stderr.",
      "radiosity"};  // named, so that --help reads the same however it was invoked
  app.require_subcommand(1);
  app.set_version_flag("--version", "radiosity 0.1.0");
  bool strict = false;
  app.add_flag("--strict", strict,
               "Treat the scene's warnings (an open refracting mesh, merged vertices, ...) as "
               "errors (exit 1)");
  bool flip_normals = false;
  app.add_flag("--flip-normals", flip_normals,
               "Turn every polygon's front side (reverse its vertex order): for a closed room "
               "modelled from outside, whose fronts face out of it (solve and render both need "
               "it: the solution is for the turned scene)");
  double progress = 5;
  app.add_option("--progress", progress,
                 "Where stderr is not a terminal (a log, a pipe), a line of progress with the "
                 "time left every this many seconds; 0: none (on a terminal a bar is drawn)")
      ->check(CLI::Range(0.0, 1e6))
      ->check(rad::cli::kFinite)
      ->capture_default_str();
  app.fallthrough();  // the global options may follow the subcommand too

  rad::cli::Run run;
  rad::cli::add_info_command(app, run);
  rad::cli::add_solve_command(app, run);
  rad::cli::add_probe_command(app, run);
  rad::cli::add_render_command(app, run);
  rad::cli::add_sweep_command(app, run);
  rad::cli::add_compare_command(app, run);
  rad::cli::add_export_command(app, run);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "radiosity: " << e.what() << "\nRun with --help for more information.\n";
    return 2;
  }

  rad::cli::set_scene_flags(strict, flip_normals);
  rad::cli::set_progress_interval(progress);
  // The commands whose work is split over an MPI job's processes; the others are the root's.
  bool distributed = false;
  for (const char* name : {"render", "probe", "sweep"})
    distributed = distributed || app.got_subcommand(name);
  int status = 0;
  if (distributed || job.is_root()) status = run_command(job, run, distributed);
  // Every process leaves together (the others wait without spinning while the root works,
  // and the root has printed before any process exits with 1).
  job.finish();
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  const rad::Job job(&argc, &argv);
  const int status = run_main(job, argc, argv);
  return job.is_root() ? checked_stdout(status) : status;
}
