#pragma once
/// Wavefront material libraries (.mtl), which OBJ files name (`mtllib`) and whose materials
/// their faces take (`usemtl`), read into scene materials (DESIGN.md §5; the table of what maps
/// to what, and why, is in docs/formats.md, "OBJ materials"):
///   Kd -> reflectance, Ke -> emission (pi Ke: Ke is a radiance, emission an exitance),
///   d (or Tr) and Tf -> transmittance, Ks and Ns -> specular and gloss when `illum` turns
///   reflection on, Ni -> ior when `illum` says glass.
/// MTL describes shading for a rasteriser: a white Kd of 1, or Kd + Ks above 1, are common and
/// have no physical counterpart; such a material is scaled down into what a surface can send on,
/// with a warning that says by how much. Textures (map_Kd, ...) are skipped with one warning.
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "scene/material.h"

namespace rad {

/// A library's materials by name.
using MaterialLibrary = std::map<std::string, Material, std::less<>>;

/// Parses the text of a material library; `file` names it in messages. Throws InputError
/// "FILE line N: ..." for a malformed statement (a number that is not one, a colour of two
/// values, a statement before the first `newmtl`, a negative or non-finite value); appends to
/// `warnings` what it changed or skipped, naming the file and the material.
MaterialLibrary parse_material_library(std::string_view text, const std::string& file,
                                       std::vector<std::string>& warnings);

}  // namespace rad
