#pragma once
/// Lambertian materials (DESIGN.md §3, §5).
#include <string>

#include "geometry/vec.h"

namespace rad {

/// A one-sided Lambertian surface material.
struct Material {
  std::string name;
  Rgb reflectance{0.5, 0.5, 0.5};  ///< rho in [0, 1) per channel; 0.5 when the file omits it.
  Rgb emission{0, 0, 0};           ///< Radiant exitance M [W/m^2] of the front side, >= 0.

  bool is_emitter() const { return (emission.array() > 0).any(); }
};

}  // namespace rad
