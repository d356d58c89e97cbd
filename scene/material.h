#pragma once
/// Materials (DESIGN.md §3, §5): one-sided Lambertian reflection and emission, plus the exact
/// extensions of paper 000: a thin non-refractive filter (§2.2) and a plane mirror (§3), and the
/// heuristic one: the interface of a refracting polyhedron (§4).
#include <optional>
#include <string>

#include "geometry/vec.h"

namespace rad {

/// The interface of a transparent polyhedron (000 §4): behind the polygon's front side lies a
/// medium of index `ior` (per channel: dispersion, §4.3), in front of it the outside, index 1.
/// Light crosses it bent by Snell's law (000 eq. 6), passing `transmittance` of itself, or the
/// Fresnel transmission at its angle when `fresnel`; inside it is dimmed by exp(-attenuation
/// length). A refracting polygon is opaque to every straight-line query (what crosses it bends),
/// and its light reaches a point only through the refracted paths.
struct Refraction {
  Rgb ior{1.5, 1.5, 1.5};      ///< n >= 1 per channel; the outside is 1
  Rgb transmittance{1, 1, 1};  ///< Fraction passed at each crossing (when !fresnel)
  bool fresnel = false;        ///< Unpolarised Fresnel transmission replaces transmittance
  Rgb attenuation{0, 0, 0};    ///< Per unit length inside, >= 0
  bool dispersive() const { return ior[0] != ior[1] || ior[1] != ior[2]; }
};

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
  /// The spread sigma (radians) of the normalised Gaussian lobe about the mirror direction
  /// that `specular` scatters into (paper 003: a glossy reflector; "gloss" in the file). 0: a
  /// perfect mirror. The solver and the eye rays take a glossy surface as the mirror of its
  /// lobe's centre; the local pass gathers its light from point lights by glossy beams
  /// (specular/glossy_transfer.h), apart from the certified part.
  double gloss = 0;
  /// A roughened pane (paper 003 Fig. 13; "transmittance" with "gloss" in the file): the
  /// fraction passed through into the lobe about the straight-through direction, from either
  /// side. Such a pane is no filter (its `transmittance` stays 0: opaque to every straight
  /// line, like a refracting interface); its light comes by glossy beams.
  Rgb glossy_transmittance{0, 0, 0};
  /// Set for the interface of a refracting polyhedron ("ior" in the file; 000 §4). Its
  /// `transmittance` above stays 0: a refracting polygon is no filter.
  std::optional<Refraction> refraction{};

  bool is_emitter() const { return (emission.array() > 0).any(); }
  /// True when some channel passes light through (the polygon is not a full occluder).
  bool is_filter() const { return (transmittance.array() > 0).any(); }
  /// True when some channel reflects specularly (sharply or glossily).
  bool is_mirror() const { return (specular.array() > 0).any(); }
  /// True for a glossy reflector: specular with a lobe of spread gloss > 0.
  bool is_glossy_mirror() const { return gloss > 0 && is_mirror(); }
  /// True for a roughened pane: glossy transmission.
  bool is_glossy_pane() const { return gloss > 0 && (glossy_transmittance.array() > 0).any(); }
  /// Either: the surface scatters into a lobe (003).
  bool is_glossy() const { return is_glossy_mirror() || is_glossy_pane(); }
  /// True for the interface of a refracting polyhedron.
  bool refracts() const { return refraction.has_value(); }
};

}  // namespace rad
