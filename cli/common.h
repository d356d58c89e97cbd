#pragma once
/// Helpers shared by the subcommands.
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "localpass/local_pass.h"
#include "radiosity/solution.h"
#include "scene/camera.h"
#include "scene/input_files.h"
#include "scene/scene.h"
#include "scene/scene_loader.h"

namespace rad::cli {

/// A byte a terminal would act on rather than show (C0 controls, ESC among them, and DEL):
/// text read from a user's file never reaches stderr or stdout with one.
inline bool is_control_byte(char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }

/// Refuses "nan", "inf" and their kin for a number option: they pass CLI11's ranges (every
/// comparison with NaN is false) and would run as a wrong setting. No text in --help.
extern const CLI::Validator kFinite;

/// The local pass's options, shared by render and probe: --tolerance (in [0, 0.99]) and
/// --samples (Monte Carlo rays per `unit`), with their defaults shown.
void add_tolerance_option(CLI::App* sub, double* tolerance, const std::string& help);
void add_samples_option(CLI::App* sub, int* samples, const std::string& unit);

/// --refraction-tolerance and --refraction-pieces, the refraction heuristic's accuracy knob
/// (LocalPassSettings; 000 §4): stored into `settings`.
void add_refraction_options(CLI::App* sub, LocalPassSettings* settings);
/// --glossy-split, --glossy-light-split, --glossy-cutoff (paper 003's beams).
void add_glossy_options(CLI::App* sub, LocalPassSettings* settings);

/// -s,--solution (a .vtp from `radiosity solve`); `detail` is appended to the help text.
CLI::Option* add_solution_option(CLI::App* sub, std::string* solution,
                                 const std::string& detail = "");
/// --width and --height overriding the camera's image size (0: the camera's); `what` names the
/// image in the help text.
void add_image_size_options(CLI::App* sub, int* width, int* height,
                            const std::string& what = "Image");
/// -j,--threads (0: all cores).
void add_threads_option(CLI::App* sub, int* threads);

/// The help text of every command's scene argument.
inline constexpr const char* kSceneHelp =
    "Scene file (JSON), or a mesh file alone (.obj with its .mtl; a camera from its bounds)";

/// The global scene flags: --strict (scene warnings become errors) and --flip-normals (every
/// polygon's front turned: SceneOptions::flip_normals).
void set_scene_flags(bool strict, bool flip_normals);
/// How every command loads its scene (--flip-normals).
SceneOptions scene_options();

/// Loads and validates a scene, printing its warnings to stderr; with --strict the first
/// warning is thrown as an InputError instead. With `files`, as load_scene (scene/input_files.h).
Scene load_scene_reporting(const std::string& path, InputFiles* files = nullptr);

/// Reads a solution file and checks that it was solved for `scene` (loaded from
/// `scene_path`). Throws InputError naming the file otherwise.
Solution load_solution_for(const Scene& scene, const std::string& scene_path,
                           const std::string& solution_path);

/// The scene's camera with the image size overridden where `width`/`height` are positive.
/// Throws InputError when the scene has no camera block.
CameraSpec camera_for(const Scene& scene, const std::string& scene_path, const std::string& command,
                      int width, int height);

/// Limits TBB to `threads` workers while alive (0: all cores).
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);

 private:
  std::unique_ptr<tbb::global_control> control_;
};

/// The one rule for refusing work before it starts: when `bytes` passes half the machine's
/// physical memory, throws InputError "NEEDS <n> GiB, more than half of this machine's <m>
/// GiB" (`needs` names the file or option and what it would make, "... needs about").
void refuse_beyond_memory(const std::string& needs, double bytes);

/// Where stderr is not a terminal (a log, a pipe, a batch job), ProgressBar prints a line every
/// this many seconds; 0 prints none. The global option --progress sets it (default 5).
void set_progress_interval(double seconds);

/// "12 s", "3 min 20 s", "2 h 05 min": a duration for people.
std::string duration_text(double seconds);

/// Progress on stderr with an estimate of the time left (time_left: from the recent rate):
/// on a terminal a one-line bar, redrawn at most 10 times a second, which finish() clears;
/// elsewhere a whole line every set_progress_interval() seconds, so that a log shows a long
/// job is alive. update() may be called from several threads (the renders report from their
/// workers).
class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();
  /// `done` in [0, 1]; `detail` is shown after the bar.
  void update(double done, const std::string& detail);
  /// A new stage of the work ("meshing", then "shooting"): its own label and its own clock
  /// for the estimate.
  void stage(const std::string& label);
  void finish();

 private:
  /// "about 3 min left", or nothing while too little is done to tell. From the rate over the
  /// last third of the stage: a solve's measure (the log of the unshot fraction) slows as it
  /// goes, and the rate since the start would promise too early an end.
  std::string time_left(double done, double now);

  std::mutex mutex_;
  std::string label_;
  bool terminal_;
  double interval_;
  double stage_start_;
  std::vector<std::pair<double, double>> history_;  ///< (time, done), one a second at most
  double last_ = -1;                                ///< Last drawn (terminal) or printed (lines)
  bool drawn_ = false;
};

}  // namespace rad::cli
