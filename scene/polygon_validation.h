#pragma once
/// Turning raw vertex lists from a file into validated scene polygons (DESIGN.md §5).
#include <string>
#include <vector>

#include "geometry/tolerance.h"
#include "scene/polygon.h"

namespace rad {

/// Tolerances of the validation, each relative to the polygon's extent (bounding-box diagonal).
struct PolygonTolerances {
  /// Consecutive vertices closer than this are one vertex (merged with a warning).
  double duplicate_vertex = relative::kRounding;
  /// A polygon whose area is below this times extent^2 has zero area (error).
  double zero_area = relative::kRounding;
  /// Vertices within this distance of the best-fit plane count as planar (float rounding in
  /// mesh files is ~6e-8).
  double planar = relative::kFloat;
  /// Up to this deviation the polygon is triangulated with a warning (the Cornell box's left
  /// wall is 3.2 mm off plane over 780 mm, ~2e-3); beyond it, it is an error.
  double non_planar_limit = 2e-2;
  /// Two non-adjacent edges closer than this are touching (self-intersection error).
  double self_touch = relative::kMatch;
};

/// True when the vertices (finite, within the coordinate limit) hold no area: fewer than 3
/// distinct vertices, or zero area, by make_polygons' own tests. A mesh face that holds none
/// carries no light and blocks none, so a mesh may drop it (mesh_object.h); make_polygons
/// refuses it.
bool holds_no_area(const std::vector<Vec3>& vertices, const PolygonTolerances& tolerances = {});

/// Validates one polygon and returns it as one polygon, or as triangles when it is slightly
/// non-planar. `where` names the element in messages ("scene.json: objects[1] polygon 4").
/// Throws InputError for: fewer than 3 (distinct) vertices, non-finite coordinates, zero area,
/// non-planar beyond the limit, self-intersection. Appends warnings for merged duplicate
/// vertices and for triangulated polygons. `material`, `object`, `source_index` are copied to
/// the results.
std::vector<Polygon> make_polygons(std::vector<Vec3> vertices, const std::string& where,
                                   int material, int object, int source_index,
                                   std::vector<std::string>& warnings,
                                   const PolygonTolerances& tolerances = {});

}  // namespace rad
