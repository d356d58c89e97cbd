#include "cli/common.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "formats/solution_io.h"
#include "octree/octree.h"
#include "scene/error.h"
#include "scene/limits.h"
#include "scene/scene_loader.h"

namespace rad::cli {

const CLI::Validator kFinite(
    [](const std::string& text) -> std::string {
      const double value = std::strtod(text.c_str(), nullptr);
      return std::isfinite(value) ? std::string() : "not a finite number: " + text;
    },
    "");

namespace {
bool strict_scenes = false;
SceneOptions global_scene_options;
}  // namespace

void set_scene_flags(bool strict, bool flip_normals) {
  strict_scenes = strict;
  global_scene_options.flip_normals = flip_normals;
}

SceneOptions scene_options() { return global_scene_options; }

Scene load_scene_reporting(const std::string& path, InputFiles* files) {
  Scene scene = load_scene(path, files, global_scene_options);
  if (strict_scenes && !scene.warnings.empty())
    throw InputError(scene.warnings.front() + " (--strict: warnings are errors)");
  for (const std::string& w : scene.warnings) std::cerr << "warning: " << w << "\n";
  return scene;
}

void refuse_beyond_memory(const std::string& needs, double bytes) {
  const double memory =
      static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGESIZE));
  if (!(memory > 0) || bytes <= 0.5 * memory) return;
  throw InputError(needs + " " + std::to_string(static_cast<long long>(bytes / (1 << 30))) +
                   " GiB, more than half of this machine's " +
                   std::to_string(static_cast<long long>(memory / (1 << 30))) + " GiB");
}

Solution load_solution_for(const Scene& scene, const std::string& scene_path,
                           const std::string& solution_path) {
  Solution solution = read_solution(solution_path);
  if (solution.scene_fingerprint != scene.fingerprint()) {
    throw InputError(solution_path + ": solved for a different scene (" + solution.scene_path +
                     "); solve " + scene_path + " again");
  }
  // The fingerprint says the scene is the same; a damaged or hostile file could still name
  // polygons it does not have.
  const auto polygons = static_cast<int>(scene.polygons.size());
  for (size_t i = 0; i < solution.patches.size(); ++i) {
    if (solution.patches[i].polygon >= polygons) {
      throw InputError(solution_path + ": patch " + std::to_string(i) + " names polygon " +
                       std::to_string(solution.patches[i].polygon) + "; the scene has " +
                       std::to_string(polygons));
    }
  }
  for (size_t i = 0; i < solution.elements.size(); ++i) {
    if (solution.elements[i].polygon >= polygons) {
      throw InputError(solution_path + ": cell " + std::to_string(i) + " names polygon " +
                       std::to_string(solution.elements[i].polygon) + "; the scene has " +
                       std::to_string(polygons));
    }
  }
  // The octree the local pass builds over the elements, at its largest (Octree::max_voxels),
  // against the machine's memory: refuse before building it.
  double corners = 0;
  for (const Element& e : solution.elements) corners += static_cast<double>(e.corners.size());
  const auto items = static_cast<long long>(solution.elements.size());
  const double octree_bytes =
      static_cast<double>(Octree::max_voxels(items)) * (sizeof(Voxel) + sizeof(int)) +
      static_cast<double>(items) * (sizeof(OctreeItem) + sizeof(int)) + corners * sizeof(Vec3);
  refuse_beyond_memory(
      solution_path + ": the octree of its " + std::to_string(items) + " elements may need",
      octree_bytes);
  return solution;
}

CameraSpec camera_for(const Scene& scene, const std::string& scene_path, const std::string& command,
                      int width, int height) {
  if (!scene.camera)
    throw InputError(scene_path + ": no \"camera\" block; " + command + " needs one");
  CameraSpec spec = *scene.camera;
  if (width > 0) spec.width = width;
  if (height > 0) spec.height = height;
  // What the images of a render take (radiosity and bound in doubles, the per-pixel counts,
  // the EXR's floats), against the machine's memory: refuse before allocating.
  constexpr double kBytesPerPixel = 2 * 24 + 3 * 4 + 1 + 4 * 4;
  const double bytes = kBytesPerPixel * spec.width * static_cast<double>(spec.height);
  const std::string source =
      width > 0 || height > 0 ? command + " --width/--height" : scene_path + ": camera";
  refuse_beyond_memory(source + ": an image of " + std::to_string(spec.width) + " x " +
                           std::to_string(spec.height) + " needs about",
                       bytes);
  return spec;
}

ThreadLimit::ThreadLimit(int threads) {
  if (threads > 0) {
    control_ = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                     threads);
  }
}

namespace {
double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
double progress_interval = 5;
}  // namespace

void set_progress_interval(double seconds) { progress_interval = seconds; }

std::string duration_text(double seconds) {
  const long long s = std::llround(std::max(0.0, seconds));
  char text[48];
  if (s < 60) {
    std::snprintf(text, sizeof text, "%lld s", s);
  } else if (s < 3600) {
    std::snprintf(text, sizeof text, "%lld min %02lld s", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof text, "%lld h %02lld min", s / 3600, s / 60 % 60);
  }
  return text;
}

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)),
      terminal_(::isatty(STDERR_FILENO) != 0),
      interval_(progress_interval),
      stage_start_(now_seconds()) {}

ProgressBar::~ProgressBar() { finish(); }

std::string ProgressBar::time_left(double done, double now) {
  if (history_.empty() || now - history_.back().first >= 1) history_.emplace_back(now, done);
  // Once a second has passed and a hundredth is done: earlier the rate says little.
  const double elapsed = now - stage_start_;
  if (!(done >= 0.01 && done < 1) || elapsed < 1) return "";
  // The first sample of the last third of the stage (at least its last second).
  const double since = now - std::max(1.0, elapsed / 3);
  const auto from = std::lower_bound(history_.begin(), history_.end(), since,
                                     [](const auto& sample, double t) { return sample.first < t; });
  if (from == history_.end() || !(done > from->second) || !(now > from->first)) return "";
  const double left = (1 - done) * (now - from->first) / (done - from->second);
  return left < 1 ? "under 1 s left" : "about " + duration_text(left) + " left";
}

void ProgressBar::stage(const std::string& label) {
  const std::lock_guard<std::mutex> lock(mutex_);
  label_ = label;
  stage_start_ = now_seconds();
  history_.clear();
}

void ProgressBar::update(double done, const std::string& detail) {
  if (!terminal_ && !(interval_ > 0)) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  const double t = now_seconds();
  done = std::clamp(done, 0.0, 1.0);
  const std::string left = time_left(done, t);
  if (terminal_) {
    if (t - last_ < 0.1) return;
    last_ = t;
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(done * kWidth);
    std::cerr << "\r" << label_ << " [" << std::string(filled, '#')
              << std::string(kWidth - filled, ' ') << "] " << detail
              << (left.empty() ? "" : ", " + left) << "\x1b[K" << std::flush;
    drawn_ = true;
    return;
  }
  if (last_ < 0) last_ = stage_start_;  // the first line after one interval
  if (t - last_ < interval_) return;
  last_ = t;
  std::cerr << label_ << ": " << static_cast<int>(100 * done) << "%, " << detail << ", "
            << duration_text(t - stage_start_) << (left.empty() ? "" : ", " + left) << "\n"
            << std::flush;
}

void ProgressBar::finish() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (drawn_) std::cerr << "\r\x1b[K" << std::flush;
  drawn_ = false;
}

void add_tolerance_option(CLI::App* sub, double* tolerance, const std::string& help) {
  sub->add_option("-t,--tolerance", *tolerance, help)
      ->check(CLI::Range(0.0, 0.99))
      ->check(kFinite)
      ->capture_default_str();
}

void add_refraction_options(CLI::App* sub, LocalPassSettings* settings) {
  sub->add_option_function<double>(
         "--refraction-tolerance", [settings](double t) { settings->refraction_tolerance = t; },
         "Refracting materials: split the first facet of each chain until the apparent-depth "
         "ratio at every facet, along the rays through each piece refracted on by Snell's law, "
         "varies by at most this much (relative); default: one angle per facet on the centroid "
         "path, paper 000 section 4's heuristic")
      ->check(CLI::Range(1e-6, 1e6))
      ->check(kFinite);
  sub->add_option("--refraction-pieces", settings->refraction_max_pieces,
                  "Refracting materials: at most this many pieces of a chain's first facet")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
}

void add_glossy_options(CLI::App* sub, LocalPassSettings* settings) {
  sub->add_option("--glossy-split", settings->glossy.split,
                  "Glossy materials (\"gloss\"): split each scatterer triangle into N x N pieces, "
                  "one beam each per source (paper 003's model is good when a piece subtends a "
                  "small angle against the lobe's spread)")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  sub->add_option("--glossy-light-split", settings->glossy.light_split,
                  "Glossy materials: split each emitting triangle into N x N point sources for "
                  "glossy transfer (point lights are used as they are)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  sub->add_option("--glossy-cutoff", settings->glossy.cutoff,
                  "Glossy materials: a beam reaches only receivers within this many lobe spreads "
                  "(sigma) of its directions (the hierarchy's cut)")
      ->check(CLI::Range(1.0, 1e9))
      ->check(kFinite)
      ->capture_default_str();
}

void add_samples_option(CLI::App* sub, int* samples, const std::string& unit) {
  sub->add_option("--samples", *samples,
                  "montecarlo: rays per " + unit + " (rounded up to a square)")
      ->check(CLI::Range(1, 1 << 24))
      ->capture_default_str();
}

CLI::Option* add_solution_option(CLI::App* sub, std::string* solution, const std::string& detail) {
  return sub->add_option("-s,--solution", *solution,
                         "Solution file (.vtp) from `radiosity solve`" + detail);
}

void add_image_size_options(CLI::App* sub, int* width, int* height, const std::string& what) {
  sub->add_option("--width", *width, what + " width in pixels (default: the camera's)")
      ->check(CLI::Range(1, limits::kImageSide));
  sub->add_option("--height", *height, what + " height in pixels (default: the camera's)")
      ->check(CLI::Range(1, limits::kImageSide));
}

void add_threads_option(CLI::App* sub, int* threads) {
  sub->add_option("-j,--threads", *threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
}

}  // namespace rad::cli
