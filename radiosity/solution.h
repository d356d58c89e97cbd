#pragma once
/// The coarse global solution: patches (shooters) subdivided into elements (receivers), after
/// Cohen, Chen, Wallace, Greenberg 1988 (substructuring) with adaptive element refinement.
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/vec.h"

namespace rad {

/// Solver parameters. Sizes are fractions of the scene's bounding-box diagonal, so defaults fit
/// any scene scale.
struct SolverSettings {
  /// Target patch edge length. Quads become near-square grids, other polygons are triangulated
  /// and each triangle subdivided uniformly. 0.08 gives ~800 patches in the Cornell box (its
  /// floor cut along the blocks' feet).
  double patch_size = 0.08;
  /// Each patch starts as 4^element_levels elements.
  int element_levels = 1;
  /// Adaptive refinement limit, relative to the local radiosity B clamped to [0.1, 1] x B_ref
  /// (near a contact or a concave edge [0.02, 1] x B_ref; B_ref: the scene's mean radiosity
  /// estimate, emitted power / total area / (1 - mean reflectance)). During a shot, an element is
  /// split in four when linear interpolation from its corners misses the radiosity it receives at
  /// its centre by more than refine_threshold * clamp(B) (near a contact or a concave edge, down to
  /// patch_size / 16: when any corner differs from the centre by more); after convergence, when it
  /// misses the plane through its neighbours by more. 0 disables refinement.
  double refine_threshold = 0.05;
  /// After convergence, up to this many passes split elements whose radiosity differs from a
  /// mesh neighbour's by more than the same limit (children re-gather exactly), then shoot on.
  int refine_passes = 3;
  /// Elements whose longest edge is below this are not split further.
  double min_element_size = 0.005;
  /// Stop when the unshot power is below this fraction of the emitted power (sum over RGB).
  double unshot_fraction = 1e-3;
  /// Stop after this many shots in any case.
  int max_shots = 200000;
  /// Shadow rays per (receiver point, shooter) pair, stratified and jittered on the shooter;
  /// rounded up to a square.
  int visibility_samples = 16;
  /// Seed of the visibility jitter; the solve is bitwise deterministic for a given seed, thread
  /// count notwithstanding.
  uint64_t seed = 1;
  /// Which solver: progressive refinement (radiosity/solver.h), or hierarchical radiosity with
  /// clustering (radiosity/hierarchical_solver.h; diffuse surfaces and point lights, so far;
  /// max_shots counts its sweeps). Not saved in the solution file.
  enum class Method { progressive, hierarchical };
  Method method = Method::progressive;
  /// Cast no shadow rays for pairs that no polygon can hide (shaft culling, geometry/shaft.h);
  /// false casts them all (the baseline the culling is measured against). Not saved in the
  /// solution file.
  bool shaft_culling = true;
  /// Hierarchical: a patch's links leave out the sources too faint to matter (Hanrahan,
  /// Salzman and Aupperle's BF refinement), as long as all it leaves out could bring it at most
  /// this many times the unshot light, unshot_fraction times the scene's mean radiosity
  /// (SolveStats::left_out_bound). 0 links every source by geometry alone, so that the links do
  /// not depend on unshot_fraction: the tests of the links' own bound compare two stops of one
  /// system. Not saved.
  double faint_share = 1;
  /// Carry refracting objects (000 §4) as filters: light crosses each interface straight,
  /// unbent, passing its transmittance (with "fresnel", the Fresnel transmission at normal
  /// incidence, 1 - ((n - 1) / (n + 1))^2). A heuristic, measured in bench/results/
  /// specular_solution.md: right in direction through a pane's parallel faces (offset sideways by
  /// its thickness), wrong by the bending through a block or a prism, and blind to the
  /// attenuation inside. False keeps them opaque and black, as the solver had them before
  /// (issue 37), and so does a scene's "refraction_depth": 0. Not saved in the solution file.
  bool glass_as_filters = true;

  /// Throws rad::Error naming the first setting out of its range.
  void validate() const;
};

/// A shooter: a planar sub-polygon of one scene polygon.
struct Patch {
  int polygon = -1;           ///< Parent polygon (index into Scene::polygons).
  std::vector<Vec3> corners;  ///< 3 or 4 corners, counter-clockwise from the front.
  Vec3 normal{0, 0, 1};
  double area = 0;
  Rgb radiosity = Rgb::Zero();  ///< Area-weighted mean of its elements' radiosity [W/m^2].
  Rgb unshot = Rgb::Zero();     ///< Radiosity received but not yet shot (Delta B).
  Rgb shot = Rgb::Zero();       ///< Radiosity shot so far (sum of its Delta B at each shot).
};

/// A receiver: a node of the quadtree that subdivides a patch. Leaves carry the solution.
struct Element {
  int patch = -1;
  int polygon = -1;
  int parent = -1;            ///< Parent element, -1 for the patch's top-level elements.
  int first_child = -1;       ///< Children are first_child .. first_child + 3; -1 for a leaf.
  int level = 0;              ///< Refinement level below the initial elements (0 = initial).
  std::vector<Vec3> corners;  ///< 3 or 4 corners, counter-clockwise from the front.
  Vec3 centroid = Vec3::Zero();
  double area = 0;
  Rgb radiosity = Rgb::Zero();   ///< B = E + rho H [W/m^2]; meaningful on leaves.
  Rgb irradiance = Rgb::Zero();  ///< H received so far [W/m^2] (kept for black receivers too).

  bool is_leaf() const { return first_child < 0; }
};

/// What the solve did, and the energy ledger (all powers in W when lengths are metres):
/// emitted = absorbed + escaped + unshot + redirected, where escaped is what shots sent that no
/// element received (light leaving an open scene, plus reciprocity error of point-sampled
/// receivers) and redirected what glossy surfaces reflect into their lobes (paper 003), which
/// the solution does not carry on.
struct SolveStats {
  int shots = 0;
  int patches = 0;
  int elements = 0;  ///< Leaves.
  int refined = 0;   ///< Elements split during the solve.
  double seconds = 0;
  Rgb emitted = Rgb::Zero();
  Rgb absorbed = Rgb::Zero();
  Rgb escaped = Rgb::Zero();
  Rgb unshot = Rgb::Zero();
  Rgb redirected = Rgb::Zero();  ///< Reflected by glossy surfaces, not carried (0 without any)
  double unshot_fraction = 0;    ///< sum(unshot) / sum(emitted)
  bool converged = false;        ///< Stopped by unshot_fraction rather than max_shots.
  /// A certified bound, per channel, on the solve's own error: max over the elements of
  /// |B* - B|, with B* the exact solution of the discrete system the solver sets up (its
  /// elements, patches and measured form factors) and B what it stopped at. It covers the
  /// iteration's error (the light not yet shot), not the discretisation's (elements taken as
  /// uniform, shadow rays' sampling, the local pass's point against an element's mean): see
  /// docs/algorithms.md, "The solution's own error". Negative: not known (a file written before
  /// the bound was kept).
  Rgb error_bound = Rgb::Constant(-1);
  /// (receiver point, shooter) pairs whose visibility was needed, and of those the ones no
  /// polygon could hide and the ones one polygon hides whole (Shooter::hides_all): no rays cast
  /// for either. Counted by the solve, not saved in the solution file.
  long long visibility_pairs = 0, unhidden_pairs = 0, hidden_pairs = 0;
  /// The hierarchical solver's links (0 for the progressive solver). Not saved.
  long long links = 0;
  /// The hierarchical solver's sources left out of the links, too faint to be worth linking
  /// (clusters and patches), and a certified bound on the irradiance they may bring any element
  /// at the final radiosity [W/m^2, largest channel] (HierarchicalSolver::reach). Not saved.
  long long left_out = 0;
  double left_out_bound = 0;
  /// The hierarchical solver's wall seconds by step: linking, the opening rounds (sources the
  /// light has reached since), the refinement passes and the sweeps (meshing is the rest of
  /// `seconds`). Not saved.
  struct Steps {
    double linking = 0, opening = 0, refining = 0, sweeping = 0;
  } steps;
};

/// A solved (or loaded) radiosity solution.
struct Solution {
  SolverSettings settings;
  SolveStats stats;
  std::vector<Patch> patches;
  std::vector<Element> elements;  ///< The whole quadtree; leaves hold the solution.
  Rgb ambient = Rgb::Zero();      ///< Cohen et al. 1988 ambient term, for display only.
  std::string scene_path;         ///< The scene file solved, as given.
  std::string scene_fingerprint;  ///< Hash of the scene's polygons (see scene_fingerprint()).

  /// Indices of the leaf elements, in index order.
  std::vector<int> leaves() const;
  /// Element e as a shooter of its own: its polygon, corners and area, its patch's normal
  /// (a piece of a patch that a receiver near it gathers from, or links to).
  Patch element_as_patch(int e) const;
};

}  // namespace rad
