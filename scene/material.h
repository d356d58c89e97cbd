#pragma once
/// Materials (DESIGN.md §3, §5): one-sided Lambertian reflection and emission, plus the exact
/// extensions of paper 000: a thin non-refractive filter (§2.2) and a plane mirror (§3).
#include <string>

#include "geometry/vec.h"

namespace rad {

/// A surface material. Per channel reflectance + transmittance + specular <= 1 (the loader
/// checks it); what is left is absorbed.
struct Material {
  std::string name;
  Rgb reflectance{0.5, 0.5, 0.5};  ///< rho in [0, 1) per channel; 0.5 when the file omits it.
  Rgb emission{0, 0, 0};           ///< Radiant exitance M [W/m^2] of the front side, >= 0.
  /// Fraction passed straight through, from either side, without refraction (a filter: stained
  /// glass, a gel; 000 §2.2). 0: opaque.
  Rgb transmittance{0, 0, 0};
  /// Plane-mirror reflectance of the front side (000 §3). 0: no mirror.
  Rgb specular{0, 0, 0};

  bool is_emitter() const { return (emission.array() > 0).any(); }
  /// True when some channel passes light through (the polygon is not a full occluder).
  bool is_filter() const { return (transmittance.array() > 0).any(); }
  /// True when some channel reflects specularly.
  bool is_mirror() const { return (specular.array() > 0).any(); }
};

}  // namespace rad
