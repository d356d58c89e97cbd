#pragma once
/// Rays in world space, shared by the camera, the ray caster and the gatherers.
#include "geometry/vec.h"

namespace rad {

/// A ray origin + t * direction, t >= 0. `direction` is unit length, so t is a distance.
struct Ray {
  Vec3 origin;
  Vec3 direction;
};

}  // namespace rad
