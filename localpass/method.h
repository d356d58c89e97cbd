#pragma once
/// The one place that maps method names to implementations. Every command (render, probe,
/// sweep), the benchmarks and the tests name methods through this enum.
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/emitting_face.h"
#include "geometry/exact_gatherer.h"
#include "scene/scene.h"

namespace rad {

/// How the local pass finds H(x).
enum class Method {
  hemisphere,  ///< exact: projection onto the hemisphere (paper 004 §3; hemisphere/)
  vertex,      ///< exact: vertex tracing with angular spans (paper 001; vertex/)
  montecarlo,  ///< sampled: cosine-weighted rays into the solution (the baseline;
               ///< reference/monte_carlo.h)
};

/// "hemisphere", "vertex", "montecarlo".
std::string method_name(Method method);
/// The method of that name, or nothing.
std::optional<Method> parse_method(std::string_view name);
/// Every method's name, in enum order (for --help and validation).
std::vector<std::string> method_names();
/// The exact methods' names.
std::vector<std::string> exact_method_names();
/// True for the exact gatherers (certified bound); false for Monte Carlo.
bool is_exact(Method method);

/// The exact gatherer of an exact method over `faces`. Throws Error for Monte Carlo.
std::unique_ptr<ExactGatherer> make_exact_gatherer(Method method, const Scene& scene,
                                                   std::vector<EmittingFace> faces);

}  // namespace rad
