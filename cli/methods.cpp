#include "cli/methods.h"

#include "scene/error.h"

namespace rad::cli {

bool MethodTraits::offered_by(MethodCommand command) const {
  switch (command) {
    case MethodCommand::render:
      return in_render;
    case MethodCommand::probe:
      return in_probe;
    case MethodCommand::sweep:
      return in_sweep;
  }
  return false;
}

const std::vector<MethodTraits>& all_methods() {
  using enum SolutionUse;
  using enum MethodKind;
  // name, kind, local, exact, solution, direct without one, distributable, render, probe, sweep
  static const std::vector<MethodTraits> methods{
      {"hemisphere", local_pass, Method::hemisphere, true, required, true, true, true, true, true},
      {"vertex", local_pass, Method::vertex, true, required, true, true, true, true, true},
      {"montecarlo", local_pass, Method::montecarlo, false, required, false, true, true, true,
       true},
      {"patches", patches, std::nullopt, false, required, false, false, true, false, false},
      {"albedo", albedo, std::nullopt, false, unused, false, false, true, false, false},
      {"facing", facing, std::nullopt, false, unused, false, false, true, false, false},
      {"pathtrace", path_tracer, std::nullopt, false, refused, false, true, true, true, false},
  };
  return methods;
}

std::vector<std::string> method_names_for(MethodCommand command) {
  std::vector<std::string> names;
  for (const MethodTraits& m : all_methods())
    if (m.offered_by(command)) names.emplace_back(m.name);
  return names;
}

std::vector<std::string> exact_method_names_for(MethodCommand command) {
  std::vector<std::string> names;
  for (const MethodTraits& m : all_methods())
    if (m.offered_by(command) && m.exact) names.emplace_back(m.name);
  return names;
}

const MethodTraits& method_traits(std::string_view name) {
  for (const MethodTraits& m : all_methods())
    if (m.name == name) return m;
  throw InputError("--method " + std::string(name) + ": no such method");
}

void check_solution_use(const MethodTraits& method, bool has_solution, MethodCommand command) {
  const std::string name(method.name);
  if (method.solution == SolutionUse::refused && has_solution)
    throw InputError("--method " + name + " traces the scene itself: it takes no --solution");
  const bool direct = command == MethodCommand::probe && method.direct_without_solution;
  if (method.solution == SolutionUse::required && !has_solution && !direct) {
    throw InputError("--method " + name +
                     " needs --solution (a .vtp written by `radiosity solve`)");
  }
}

}  // namespace rad::cli
