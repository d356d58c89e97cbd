#pragma once
/// Isotropic point lights (issue 20; paper 003 §3.1 starts its beams at one): the top-level
/// "lights" of a scene file. A point light of intensity I [W/sr] gives a point x with unit
/// normal n, at distance r in direction w, the irradiance I max(0, n . w) / r^2 times what the
/// polygons on the segment pass (0 through an opaque one): exact, as a point has no extent.
#include "geometry/vec.h"

namespace rad {

struct PointLight {
  Vec3 position = Vec3::Zero();
  Rgb intensity = Rgb::Zero();  ///< Radiant intensity [W/sr] per channel, the same every way

  /// The irradiance it gives x with unit normal n if nothing lies between (the inverse-square
  /// cosine law); 0 behind x's plane and at the light itself.
  Rgb unoccluded_irradiance(const Vec3& x, const Vec3& n) const {
    const Vec3 to = position - x;
    const double r2 = to.squaredNorm();
    const double cosine = n.dot(to);
    if (!(r2 > 0) || !(cosine > 0)) return Rgb::Zero();
    return intensity * (cosine / (r2 * std::sqrt(r2)));
  }
};

}  // namespace rad
