// `radiosity solve SCENE -o SOLUTION.vtp`: mesh the scene and run progressive radiosity.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>

#include "cli/commands.h"
#include "cli/common.h"
#include "formats/atomic_file.h"
#include "formats/solution_io.h"
#include "radiosity/hierarchical_solver.h"
#include "radiosity/solver.h"
#include "scene/ray_caster.h"

namespace rad::cli {
namespace {

struct SolveOptions {
  std::string scene;
  std::string output;
  SolverSettings settings;
  int threads = 0;
};

std::string rgb(const Rgb& v) {
  std::ostringstream out;
  out << std::setprecision(6) << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return out.str();
}

/// Refuses, before any work, a mesh that would need more than half the machine's memory, with
/// the number of elements and the memory it would need at the least (least_mesh_needs).
void refuse_mesh_beyond_memory(const Scene& scene, const SolveOptions& o) {
  const MeshNeeds needs = least_mesh_needs(scene, o.settings);
  std::ostringstream what;
  what << o.scene << ": meshed at --patch-size " << o.settings.patch_size
       << " and --element-levels " << o.settings.element_levels << " it makes at least "
       << static_cast<long long>(needs.elements) << " elements (raise --patch-size or lower "
       << "--element-levels), which need at least";
  refuse_beyond_memory(what.str(), needs.bytes);
}

void run_solve(const SolveOptions& o) {
  const ThreadLimit limit(o.threads);
  const Scene scene = load_scene_reporting(o.scene);
  check_outputs({{"the solution (-o)", o.output}});  // before the work, not after it
  refuse_mesh_beyond_memory(scene, o);
  const RayCaster caster(scene);
  SolverSettings settings = o.settings;
  if (settings.method == SolverSettings::Method::hierarchical) {
    if (const std::string missing = hierarchical_unsupported(scene); !missing.empty()) {
      std::cerr << "solve: the hierarchical solver does not carry " << missing
                << " yet; solving progressively\n";
      settings.method = SolverSettings::Method::progressive;
    }
  }
  using Stage = SolveProgress::Stage;
  // The stages that report the fraction done: their label, and what the fraction counts.
  const std::map<Stage, std::pair<const char*, const char*>> counted{
      {Stage::meshing, {"solve (meshing)", "polygons into patches and elements"}},
      {Stage::burying, {"solve (burying)", "elements inside closed objects found"}},
      {Stage::linking, {"solve (linking)", "patches linked to their sources"}},
      {Stage::opening, {"solve (opening)", "patches' faint sources reached by the light opened"}},
      {Stage::refining, {"solve (refining)", "elements tested, then the new ones linked"}}};
  ProgressBar bar("solve (meshing)");
  Stage shown = Stage::meshing;
  Solution solution = solve(caster, settings, [&](const SolveProgress& p) {
    const auto fraction = counted.find(p.stage);
    if (p.stage != shown) {
      shown = p.stage;
      bar.stage(fraction != counted.end()                                 ? fraction->second.first
                : settings.method == SolverSettings::Method::hierarchical ? "solve (gathering)"
                                                                          : "solve (shooting)");
    }
    if (fraction != counted.end()) {
      bar.update(p.stage_done, fraction->second.second);
      return;
    }
    // Progress on a log scale: from 1 (nothing shot) to the target fraction.
    const double done = std::log(std::max(p.unshot_fraction, 1e-300)) / std::log(p.target_fraction);
    std::ostringstream detail;
    detail << (settings.method == SolverSettings::Method::hierarchical ? "change " : "unshot ")
           << std::setprecision(3) << 100 * p.unshot_fraction << "% (target "
           << 100 * p.target_fraction << "%), "
           << (settings.method == SolverSettings::Method::hierarchical ? "sweep " : "shot ")
           << p.shots << ", elements " << p.elements;
    bar.update(done, detail.str());
  });
  bar.finish();
  solution.scene_path = o.scene;
  solution.scene_fingerprint = scene.fingerprint();
  write_solution(o.output, solution, scene);

  const SolveStats& s = solution.stats;
  std::cerr << std::setprecision(4) << "solve: " << s.patches << " patches, " << s.elements
            << " elements (" << s.refined << " split), " << s.shots
            << (s.links > 0 ? " sweeps over " + std::to_string(s.links) + " links, last change "
                            : " shots, unshot ")
            << 100 * s.unshot_fraction << "% of emitted"
            << (s.converged ? "" : " (stopped at --max-shots)") << ", " << s.seconds << " s\n"
            << "visibility: " << s.visibility_pairs << " point-patch pairs, "
            << 100.0 * s.unhidden_pairs / std::max(1LL, s.visibility_pairs)
            << "% with nothing between them, "
            << 100.0 * s.hidden_pairs / std::max(1LL, s.visibility_pairs)
            << "% hidden whole by one polygon (no shadow rays for either)\n"
            << "energy: emitted " << rgb(s.emitted) << " = absorbed " << rgb(s.absorbed)
            << " + escaped " << rgb(s.escaped) << " + unshot " << rgb(s.unshot)
            << (s.redirected == Rgb::Zero()
                    ? ""
                    : " + redirected by glossy surfaces, not carried " + rgb(s.redirected))
            << "\n"
            << "solution's own error: every element within " << rgb(s.error_bound)
            << " W/m^2 of the exact solution of its discrete system (certified; "
            << (s.links > 0 ? "the sweeps not yet made, not the links' approximations"
                            : "the light not yet shot")
            << ", not the meshing: docs/algorithms.md)\n";
  if (s.links > 0) {
    std::cerr << "left out of the links: " << s.left_out
              << " faint clusters and patches, bringing any element at most " << s.left_out_bound
              << " W/m^2 of irradiance (certified, at the final radiosity)\n"
              << "time: linking " << s.steps.linking << " s, opening the sources the light "
              << "reached " << s.steps.opening << " s, refining " << s.steps.refining
              << " s, sweeps " << s.steps.sweeping << " s\n";
  }
  std::cerr << "wrote " << o.output << "\n";
}

}  // namespace

void add_solve_command(CLI::App& app, Run& run) {
  auto o = std::make_shared<SolveOptions>();
  SolverSettings& s = o->settings;
  // The command's default is the hierarchical solver: on every scene of bench/ but the IFC
  // house it is the faster, at the same accuracy (docs/algorithms.md, "The hierarchical
  // solver"); what it does not carry falls back to the progressive solver, with a line.
  s.method = SolverSettings::Method::hierarchical;
  CLI::App* sub = app.add_subcommand(
      "solve", "Mesh the scene and solve its radiosity; write the solution (.vtp).");
  sub->footer(
      "--solver progressive: progressive refinement radiosity (Cohen, Chen, Wallace, Greenberg\n"
      "1988) in RGB, every feature: polygons are cut along their contact lines (a block's foot\n"
      "on a floor), then into patches (shooters) of edge --patch-size x the scene diagonal, each\n"
      "4^--element-levels elements (receivers); what lies inside closed objects is buried and\n"
      "takes no part. The patch with the most unshot power shoots, each element receiving\n"
      "Delta B x FF x V at its centroid (FF: Lambert's formula; V: the share of\n"
      "--visibility-samples jittered shadow rays that pass; each pair measured once for all\n"
      "shots); elements near the shooter receive it piece by piece. Elements are split where\n"
      "linear interpolation misses the received radiosity by more than --refine-threshold (near\n"
      "a contact or concave edge: where any corner does), during shots and in --refine-passes\n"
      "passes afterwards. Stops when the unshot power is below --unshot of the emitted.\n"
      "--solver hierarchical (the default): hierarchical radiosity with clustering (Hanrahan,\n"
      "Salzman, Aupperle 1991; Smits, Arvo, Greenberg 1994) on the same mesh: each patch is\n"
      "linked to whole clusters of patches far from it, to patches, or element by element\n"
      "near it; sources too faint to matter are left out, as long as all a patch leaves out\n"
      "may bring it at most --unshot of the mean radiosity, and opened as the light reaches\n"
      "them. Jacobi sweeps gather over the links until the last sweep's change is below\n"
      "--unshot of the emitted power (--max-shots counts sweeps); then --refine-passes passes\n"
      "split the elements off their neighbours' plane (near a contact: where any corner is),\n"
      "each new element measuring its own links, and sweep again. Point lights shoot once,\n"
      "first; scenes with filters, refracting objects, mirrors or glossy surfaces are solved\n"
      "progressively, with a line that says so. The two against each other:\n"
      "bench/results/hierarchical_solve.md.\n"
      "Prints a summary (hierarchical: with the seconds of each step), the energy ledger\n"
      "(emitted = absorbed + escaped + unshot [+ redirected: what glossy surfaces reflect into\n"
      "their lobes, not carried]) and a certified bound on the solution's own error on\n"
      "stderr. Bitwise deterministic for a seed, whatever the thread count. Accuracy against\n"
      "time: bench/results/global_accuracy.md. The algorithms: docs/algorithms.md.\n"
      "Shows its progress with the time left (a bar on a terminal, else a line every --progress\n"
      "seconds). Refuses before any work a mesh that would need more than half the machine's\n"
      "memory, with the elements and memory it would need at the least. Interrupted, it\n"
      "leaves no partial file.");
  sub->add_option("scene", o->scene, kSceneHelp)->required();
  sub->add_option("-o,--output", o->output, "Solution file (.vtp, opens in ParaView)")->required();
  sub->add_option("--patch-size", s.patch_size,
                  "Patch edge length, as a fraction of the scene's diagonal")
      ->check(CLI::Range(1e-4, 1.0))
      ->check(kFinite)
      ->capture_default_str();
  sub->add_option("--element-levels", s.element_levels, "Initial elements per patch: 4^levels")
      ->check(CLI::Range(0, 6))
      ->capture_default_str();
  sub->add_option("--refine-threshold", s.refine_threshold,
                  "Split an element where its radiosity is off linear (during a shot) or off its "
                  "neighbours' (after convergence; hierarchical: only then) by more than this "
                  "fraction of the local radiosity (0: no adaptive refinement)")
      ->check(CLI::Range(0.0, 1e6))
      ->check(kFinite)
      ->capture_default_str();
  sub->add_option("--refine-passes", s.refine_passes,
                  "After convergence, passes that split elements differing from a neighbour by "
                  "more than the threshold")
      ->check(CLI::Range(0, 20))
      ->capture_default_str();
  sub->add_option("--min-element-size", s.min_element_size,
                  "Smallest element edge, as a fraction of the diagonal")
      ->check(CLI::Range(1e-6, 1.0))
      ->check(kFinite)
      ->capture_default_str();
  sub->add_option("--unshot", s.unshot_fraction,
                  "Stop when the unshot power (hierarchical: the last sweep's change) is below "
                  "this fraction of the emitted (hierarchical: and leave out of the links the "
                  "sources that may bring a patch at most this fraction of the mean radiosity)")
      ->check(CLI::Range(1e-12, 0.999999))
      ->check(kFinite)
      ->capture_default_str();
  sub->add_option("--max-shots", s.max_shots,
                  "Stop after this many shots (hierarchical: sweeps) in any case")
      ->check(CLI::Range(0, 100000000))
      ->capture_default_str();
  sub->add_option("--visibility-samples", s.visibility_samples,
                  "Shadow rays per receiver point and shooter")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  sub->add_option("--solver", s.method,
                  "progressive: progressive refinement (every feature); hierarchical: hierarchical "
                  "radiosity with clustering (diffuse surfaces and point lights; others are solved "
                  "progressively, with a line that says so)")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, SolverSettings::Method>{
              {"progressive", SolverSettings::Method::progressive},
              {"hierarchical", SolverSettings::Method::hierarchical}},
          CLI::ignore_case))
      ->default_str("hierarchical");
  sub->add_option("--seed", s.seed, "Seed of the shadow-ray jitter")->capture_default_str();
  sub->add_flag("--opaque-glass{false}", s.glass_as_filters,
                "Keep refracting objects opaque and black to the solver (by default light "
                "crosses them unbent, passing their transmittance)");
  add_threads_option(sub, &o->threads);
  sub->callback([o, &run] { run = [o] { run_solve(*o); }; });
}

}  // namespace rad::cli
