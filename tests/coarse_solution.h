#pragma once
/// A bundled scene and a quick, coarse radiosity solution of it, its leaf elements as faces that
/// radiate their radiosity (what the local pass gathers from). Shared by the tests that need a
/// solution without the cost of the default one.
#include <filesystem>
#include <string>
#include <vector>

#include "radiosity/solution_faces.h"
#include "radiosity/solver.h"
#include "scene/polygon_faces.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"

namespace rad::test {

struct SolvedScene {
  Scene scene;
  std::vector<EmittingFace> faces;
};

/// data/<name>/scene.json, solved with large patches, one refinement pass and a loose stop
/// (about 4,000 elements for the Cornell box, refined along its contacts; about a second).
inline SolvedScene solve_coarse(const std::string& name) {
  SolvedScene s;
  s.scene = load_scene(std::filesystem::path(RAD_SOURCE_DIR) / "data" / name / "scene.json");
  SolverSettings settings;
  settings.patch_size = 0.25;
  settings.refine_threshold = 0.2;
  settings.refine_passes = 1;
  settings.unshot_fraction = 1e-2;
  s.faces = faces_from_solution(s.scene, solve(RayCaster(s.scene), settings));
  return s;
}

/// The Cornell box's coarse solution, solved once per test program.
inline const SolvedScene& coarse_cornell() {
  static const SolvedScene s = solve_coarse("cornell-box");
  return s;
}

}  // namespace rad::test
