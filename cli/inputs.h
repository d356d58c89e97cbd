#pragma once
/// A command's inputs, the scene and its solution, on every process of an MPI job.
#include <optional>
#include <string>

#include "distributed/job.h"
#include "radiosity/solution.h"
#include "scene/scene.h"

namespace rad::cli {

struct Inputs {
  Scene scene;
  std::optional<Solution> solution;  ///< when a solution path was given
};

/// Loads the scene at `scene_path` and, unless `solution_path` is empty, the solution solved for
/// it (load_scene_reporting, load_solution_for). In a job of one, that is all. Over an MPI job
/// the root alone reads the files (the scene, the meshes it names, the solution), checks them
/// and prints the scene's warnings, then broadcasts their bytes; every other process parses
/// those bytes (the solution from a private copy in its temporary folder, $TMPDIR), so that all
/// hold the same scene. A failure anywhere fails on every process (Job::step): the root's own
/// message when its files are bad, "process K: ..." when process K could not parse or stage
/// what it was sent.
Inputs load_inputs(const Job& job, const std::string& scene_path, const std::string& solution_path);

}  // namespace rad::cli
