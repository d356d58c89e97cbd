#include "cli/inputs.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "cli/common.h"
#include "scene/error.h"
#include "scene/input_files.h"
#include "scene/scene_loader.h"

namespace rad::cli {
namespace {

/// The solution from `bytes` (the root's copy of `solution_path`): VTK's reader and the
/// structure check (formats/vtp_guard.h) read files, so the bytes go to a private file in the
/// temporary folder first, removed afterwards.
Solution load_sent_solution(const Scene& scene, const std::string& scene_path,
                            const std::string& solution_path, const std::string& bytes) {
  std::filesystem::path staged;
  try {
    staged = std::filesystem::temp_directory_path() /
             ("radiosity-" + std::to_string(::getpid()) + "-" +
              std::filesystem::path(solution_path).filename().string());
  } catch (const std::filesystem::filesystem_error& e) {
    throw InputError("cannot copy " + solution_path +
                     " to a temporary folder ($TMPDIR): " + e.code().message());
  }
  struct Remove {
    const std::filesystem::path& file;
    ~Remove() {
      std::error_code ignored;
      std::filesystem::remove(file, ignored);
    }
  } remove{staged};
  {
    std::ofstream out(staged, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out.flush()) throw InputError("cannot copy " + solution_path + " to " + staged.string());
  }
  return load_solution_for(scene, scene_path, staged.string());
}

}  // namespace

Inputs load_inputs(const Job& job, const std::string& scene_path,
                   const std::string& solution_path) {
  if (!job.distributed()) {
    Inputs in{load_scene_reporting(scene_path), std::nullopt};
    if (!solution_path.empty())
      in.solution = load_solution_for(in.scene, scene_path, solution_path);
    return in;
  }
  InputFiles files;
  std::optional<Scene> scene;
  std::optional<Solution> solution;
  job.step([&] {
    if (!job.is_root()) return;
    scene = load_scene_reporting(scene_path, &files);
    if (solution_path.empty()) return;
    solution = load_solution_for(*scene, scene_path, solution_path);
    files.read(solution_path, "solution file");
  });
  const std::string sent = job.broadcast(job.is_root() ? files.serialize() : std::string());
  job.step([&] {
    if (job.is_root()) return;
    files = InputFiles::deserialize(sent);
    scene = load_scene(scene_path, &files, scene_options());  // the root printed its warnings
    if (solution_path.empty()) return;
    const std::string* bytes = files.find(solution_path);
    if (!bytes) throw Error(solution_path + ": not among the files the root sent");
    solution = load_sent_solution(*scene, scene_path, solution_path, *bytes);
  });
  return {std::move(*scene), std::move(solution)};
}

}  // namespace rad::cli
