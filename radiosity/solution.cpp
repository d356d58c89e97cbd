#include "radiosity/solution.h"

#include <cmath>
#include <string>

#include "scene/error.h"

namespace rad {

void SolverSettings::validate() const {
  auto bad = [](const std::string& what) { throw Error("solver settings: " + what); };
  if (!(patch_size > 0 && patch_size <= 1)) bad("patch_size must be in (0, 1]");
  if (element_levels < 0 || element_levels > 6) bad("element_levels must be in [0, 6]");
  if (!(refine_threshold >= 0)) bad("refine_threshold must be >= 0");
  if (refine_passes < 0 || refine_passes > 20) bad("refine_passes must be in [0, 20]");
  if (!(min_element_size > 0)) bad("min_element_size must be > 0");
  if (!(unshot_fraction > 0 && unshot_fraction < 1)) bad("unshot_fraction must be in (0, 1)");
  if (!(faint_share >= 0 && std::isfinite(faint_share))) bad("faint_share must be finite, >= 0");
  if (max_shots < 0) bad("max_shots must be >= 0");
  if (visibility_samples < 1) bad("visibility_samples must be >= 1");
}

std::vector<int> Solution::leaves() const {
  std::vector<int> out;
  for (size_t e = 0; e < elements.size(); ++e) {
    if (elements[e].is_leaf()) out.push_back(static_cast<int>(e));
  }
  return out;
}

Patch Solution::element_as_patch(int e) const {
  const Element& piece = elements[e];
  Patch part;
  part.polygon = piece.polygon;
  part.corners = piece.corners;
  part.normal = patches[piece.patch].normal;
  part.area = piece.area;
  return part;
}

}  // namespace rad
