#pragma once
/// The one registry of the methods a command can name, with their traits: render, probe and
/// sweep take their names, their --method checks and their input-check messages from here. The
/// local pass's own three methods are an enum of localpass/method.h (which builds their
/// gatherers); the plain renders and the path tracer are named here only.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "localpass/method.h"

namespace rad::cli {

/// The commands that name methods.
enum class MethodCommand { render, probe, sweep };

/// What a method does with a solution file (--solution).
enum class SolutionUse {
  required,  ///< it renders B from the solution's elements (the local pass, patches)
  refused,   ///< it traces the scene itself (the path tracer): a solution would be ignored
  unused,    ///< it shows the scene's materials only (albedo, facing)
};

/// What computes a method's values: the one thing commands dispatch on (never its name).
enum class MethodKind {
  local_pass,   ///< B = E + rho H with H gathered from a solution (localpass/method.h's Method)
  path_tracer,  ///< the reference: the scene itself path-traced (reference/path_tracer.h)
  patches,      ///< the solution's element radiosities, Gouraud-interpolated
  albedo,       ///< primary rays: reflectance, emitters their emission
  facing,       ///< albedo x |cos| to the eye
};

struct MethodTraits {
  std::string_view name;
  MethodKind kind = MethodKind::local_pass;
  std::optional<Method> local;  ///< The local pass's method, for hemisphere, vertex, montecarlo.
  bool exact = false;           ///< A certified bound on every value (hemisphere, vertex).
  SolutionUse solution = SolutionUse::unused;
  /// probe: without a solution, the exact direct lighting of the scene (hemisphere, vertex).
  bool direct_without_solution = false;
  /// Splits its pixels or points over the processes of an MPI job (docs/cluster.md).
  bool distributable = false;
  bool in_render = false, in_probe = false, in_sweep = false;

  bool offered_by(MethodCommand command) const;
};

/// Every method, in the order --help lists them.
const std::vector<MethodTraits>& all_methods();
/// The names `command` offers (for CLI11's IsMember check and --help).
std::vector<std::string> method_names_for(MethodCommand command);
/// The exact methods' names (sweep's reference).
std::vector<std::string> exact_method_names_for(MethodCommand command);
/// The method of that name. Throws InputError for a name no command offers (CLI11 checks the
/// names before a command runs, so this is for callers that did not).
const MethodTraits& method_traits(std::string_view name);

/// Throws InputError with one line when `method` cannot run in `command` with (or without) a
/// solution: "--method pathtrace traces the scene itself: it takes no --solution", or
/// "--method X needs --solution (a .vtp written by `radiosity solve`)".
void check_solution_use(const MethodTraits& method, bool has_solution, MethodCommand command);

}  // namespace rad::cli
