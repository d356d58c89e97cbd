#include "localpass/method.h"

#include <array>

#include "hemisphere/hemisphere_gatherer.h"
#include "scene/error.h"
#include "vertex/vertex_tracer.h"

namespace rad {
namespace {

constexpr std::array<std::pair<Method, std::string_view>, 3> kNames{
    {{Method::hemisphere, "hemisphere"},
     {Method::vertex, "vertex"},
     {Method::montecarlo, "montecarlo"}}};

}  // namespace

std::string method_name(Method method) {
  for (const auto& [m, name] : kNames) {
    if (m == method) return std::string(name);
  }
  return "unknown";
}

std::optional<Method> parse_method(std::string_view name) {
  for (const auto& [m, n] : kNames) {
    if (n == name) return m;
  }
  return std::nullopt;
}

std::vector<std::string> method_names() {
  std::vector<std::string> out;
  for (const auto& [m, name] : kNames) out.emplace_back(name);
  return out;
}

std::vector<std::string> exact_method_names() {
  std::vector<std::string> out;
  for (const auto& [m, name] : kNames) {
    if (is_exact(m)) out.emplace_back(name);
  }
  return out;
}

bool is_exact(Method method) { return method != Method::montecarlo; }

std::unique_ptr<ExactGatherer> make_exact_gatherer(Method method, const Scene& scene,
                                                   std::vector<EmittingFace> faces) {
  switch (method) {
    case Method::hemisphere:
      // Its visibility is opaque by construction (004 §3: each polygon clips what lies behind
      // it away); filters need the depth-ordered spans of vertex tracing (000 §2.2).
      for (const EmittingFace& f : faces) {
        if (f.transmittance != Rgb::Zero()) {
          throw Error("hemisphere: " + scene.describe_polygon(f.polygon) +
                      " is a filter (transmittance > 0), which the hemisphere method does not "
                      "support; use --method vertex");
        }
      }
      return std::make_unique<HemisphereGatherer>(std::move(faces), scene.tolerance());
    case Method::vertex:
      return std::make_unique<VertexTracer>(scene, std::move(faces));
    case Method::montecarlo:
      break;
  }
  throw Error("method " + method_name(method) + " is not an exact gatherer");
}

}  // namespace rad
