#pragma once
/// Progressive refinement radiosity (Cohen, Chen, Wallace, Greenberg 1988) with substructuring
/// and adaptive element refinement.
#include <functional>

#include "radiosity/solution.h"
#include "scene/ray_caster.h"

namespace rad {

/// Reported while the mesh is made, and after every shot.
struct SolveProgress {
  /// What the solve is doing: cutting and splitting the polygons into patches and elements,
  /// finding the elements buried inside closed objects, and, in the hierarchical solver,
  /// linking receivers to sources, opening the sources the light has reached since, and
  /// splitting elements (refinement) with their new links (for these, `stage_done` is the
  /// fraction done); or shooting (the fields below; the hierarchical solver's sweeps count as
  /// shots).
  enum class Stage { meshing, burying, linking, opening, refining, shooting };
  Stage stage = Stage::shooting;
  double stage_done = 0;
  int shots = 0;
  double unshot_fraction = 1;  ///< Current unshot power / emitted power.
  double target_fraction = 0;  ///< Where the solve stops.
  int elements = 0;            ///< Current leaves.
};

/// Meshes the caster's scene and solves it:
///   1. polygons cut along their contact lines (radiosity/contact_cuts.h), then patches of
///      settings.patch_size, each split into 4^element_levels elements; elements inside
///      closed objects are buried (Shooter::is_buried) and take no part;
///   2. repeatedly shoot the patch with the largest unshot power sum_c |Delta B_c| * A: every
///      leaf element e receives H_e = Delta B * FF(x_e, patch) * V, with FF the exact unoccluded
///      point-to-patch form factor at the element's centroid (Lambert) and V the fraction of
///      `visibility_samples` stratified jittered shadow rays to the patch that are unblocked;
///      B_e += rho_e H_e and the element's patch gains rho_e H_e A_e / A_patch of unshot
///      radiosity. Elements where this shot's radiosity is far from linear are split first
///      (see SolverSettings::refine_threshold). Receivers close to the shooter gather it piece
///      by piece instead (radiosity/near_field.h), and a pair's visible form factor is measured
///      once for all the shots (radiosity/form_factor_store.h);
///   3. stop when the unshot power falls below settings.unshot_fraction of the emitted power;
///   4. up to settings.refine_passes times, split elements their neighbours' plane mispredicts,
///      let the children re-gather what has been shot, and shoot on to convergence.
/// New elements always re-gather (exact, see ProgressiveSolver::regather); the difference to
/// what they inherited is shot as a correction, negative where they hold less.
/// Glossy surfaces (paper 003): a glossy mirror's specular part is not carried (the ledger's
/// `redirected`); a roughened pane is carried as the filter of its glossy transmittance.
/// Refracting objects are carried as filters, unbent (SolverSettings::glass_as_filters).
/// Parallel over receivers (TBB); bitwise deterministic for a given seed whatever the thread
/// count. Throws Error for invalid settings. With settings.method hierarchical, it is
/// solve_hierarchical() instead (radiosity/hierarchical_solver.h).
Solution solve(const RayCaster& caster, const SolverSettings& settings,
               const std::function<void(const SolveProgress&)>& progress = {});

/// What a solve's mesh needs at the least, known before it is made: the elements (at least
/// least_patches() x 4^element_levels) and the bytes
/// the solver keeps for each (the element, its corners, its radiosity's working copies). The
/// refinement and the form factors' store come on top. For refusing a scene before the work.
struct MeshNeeds {
  double elements = 0;
  double bytes = 0;
};
MeshNeeds least_mesh_needs(const Scene& scene, const SolverSettings& settings);

/// Mean radiosity estimate used to scale refinement: per channel, emitted power / total area /
/// (1 - area-weighted mean reflectance); the largest channel.
double reference_radiosity(const Scene& scene);

}  // namespace rad
