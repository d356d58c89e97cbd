#pragma once
/// Checks of a whole loaded scene, whatever file it came from (a scene file, a bare mesh): what
/// would overflow (an error), and what would make its light go nowhere it can be seen (warnings).
#include <string>

#include "scene/scene.h"

namespace rad {

/// Refuses a scene whose light would overflow the arithmetic (limits::kPower), naming the first
/// element whose power passes the limit, or the total when none alone does. `file` starts the
/// message.
void check_power(const Scene& scene, const std::string& file);

/// 000 §4 follows light into a polyhedron and out through another of its facets: an object with
/// refracting polygons should be closed, with its fronts facing out. Warns otherwise, naming
/// the object by `where`.
void check_refracting_closure(const std::string& where, const SceneObject& object, Scene& scene);

/// Warns when nothing emits, and when the lights face no receiver: no polygon's front side sees an
/// emitter's front side or a point light (every receiver is behind every light, so the solution is
/// black). That is what a closed room modelled from outside gives, its fronts facing out of it (a
/// Blender cube): the warning says so and names --flip-normals. Two polygons face each other when
/// each has a vertex strictly in front of the other's plane. Cost: O(n) per light, over at most 64
/// of the emitting polygons (spread over the list) and 64 point lights, until one faces a receiver.
void check_facing(Scene& scene);

}  // namespace rad
