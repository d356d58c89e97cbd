#include "scene/scene_checks.h"

#include <algorithm>
#include <numbers>
#include <sstream>

#include "scene/closed_surface.h"
#include "scene/error.h"
#include "scene/limits.h"

namespace rad {
namespace {

/// How far in front of `p`'s plane `x` lies (its first vertex is on the plane).
double height_above(const Polygon& p, const Vec3& x) { return p.normal.dot(x - p.vertices[0]); }

/// True when some vertex of `q` lies more than `eps` in front of `p`'s plane.
bool in_front(const Polygon& p, const Polygon& q, double eps) {
  return std::any_of(q.vertices.begin(), q.vertices.end(),
                     [&](const Vec3& v) { return height_above(p, v) > eps; });
}

/// Up to `most` indices spread evenly over [0, n).
std::vector<size_t> spread(size_t n, size_t most) {
  std::vector<size_t> picked;
  const size_t step = std::max<size_t>(1, n / most);
  for (size_t i = 0; i < n && picked.size() < most; i += step) picked.push_back(i);
  return picked;
}

}  // namespace

void check_power(const Scene& scene, const std::string& file) {
  const auto too_much = [](double watts) { return !(watts <= limits::kPower); };
  std::ostringstream limit;
  limit << limits::kPower;
  for (size_t i = 0; i < scene.polygons.size(); ++i) {
    const Polygon& p = scene.polygons[i];
    if (too_much(scene.materials[p.material].emission.maxCoeff() * p.area)) {
      throw InputError(file + ": " + scene.describe_polygon(static_cast<int>(i)) +
                       ": emits more than " + limit.str() +
                       " W (emission times area): the arithmetic would overflow");
    }
  }
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    if (too_much(4 * std::numbers::pi * scene.lights[i].intensity.maxCoeff())) {
      throw InputError(file + ": lights[" + std::to_string(i) + "]: emits more than " +
                       limit.str() + " W (4 pi intensity): the arithmetic would overflow");
    }
  }
  // No element alone passes the limit; all of them together may (Scene's own sums).
  if (too_much((scene.emitted_power() + scene.light_power()).maxCoeff())) {
    throw InputError(file + ": top level: the lights emit more than " + limit.str() +
                     " W in all: the arithmetic would overflow");
  }
}

void check_refracting_closure(const std::string& where, const SceneObject& object, Scene& scene) {
  const bool refracts =
      std::any_of(scene.polygons.begin() + object.first_polygon,
                  scene.polygons.begin() + object.first_polygon + object.polygon_count,
                  [&](const Polygon& p) { return scene.materials[p.material].refracts(); });
  if (!refracts) return;
  const SurfaceClosure closure =
      surface_closure(scene.polygons, object.first_polygon, object.polygon_count);
  if (closure.unpartnered_edges > 0) {
    scene.warnings.push_back(
        where + ": refracting but not closed (" + std::to_string(closure.unpartnered_edges) +
        " edges without a reversed partner); light that enters it may not leave");
  } else if (!(closure.volume > 0)) {
    scene.warnings.push_back(where +
                             ": refracting with its fronts facing in (the index is of "
                             "the medium behind the front side)");
  }
}

void check_facing(Scene& scene) {
  const double eps = scene.tolerance().pad;
  std::vector<size_t> emitters;
  for (size_t i = 0; i < scene.polygons.size(); ++i)
    if (scene.materials[scene.polygons[i].material].is_emitter()) emitters.push_back(i);
  if (emitters.empty() && scene.lights.empty()) {
    scene.warnings.push_back(scene.path.string() +
                             ": nothing emits light (no material has an emission, or an MTL's "
                             "Ke, and there are no point lights): every result is black");
    return;
  }
  constexpr size_t kMostLights = 64;
  for (const size_t e : spread(emitters.size(), kMostLights)) {
    const Polygon& emitter = scene.polygons[emitters[e]];
    for (size_t r = 0; r < scene.polygons.size(); ++r) {
      const Polygon& receiver = scene.polygons[r];
      if (r != emitters[e] && in_front(emitter, receiver, eps) && in_front(receiver, emitter, eps))
        return;
    }
  }
  for (const size_t l : spread(scene.lights.size(), kMostLights)) {
    for (const Polygon& receiver : scene.polygons)
      if (height_above(receiver, scene.lights[l].position) > eps) return;
  }
  scene.warnings.push_back(
      scene.path.string() +
      ": no polygon faces a light (every receiver's front is turned away from every emitter), "
      "so nothing will be lit: are the normals facing out of a closed room, as a room modelled "
      "from outside has them? --flip-normals turns every polygon");
}

}  // namespace rad
