#pragma once
/// What the exact gatherers see: convex planar faces, each a piece of one scene polygon, with
/// the exitance it radiates from its front. Direct lighting uses the polygons themselves (concave
/// ones as triangles); radiosity reconstruction uses the solution's leaf elements, so that every
/// patch emits its own radiosity (001 §4.2). Both exact methods take the same faces, so they
/// can be compared face for face.
#include <vector>

#include "radiosity/solution.h"
#include "scene/scene.h"

namespace rad {

struct EmittingFace {
  int polygon = -1;           ///< The scene polygon it is part of (its plane, its occlusion).
  std::vector<Vec3> vertices; ///< Convex, counter-clockwise about the polygon's normal.
  Rgb exitance = Rgb::Zero(); ///< Radiated from the front side only [W/m^2].
  /// Per edge i (vertices i -> i+1): true when it lies on the polygon's boundary. Only such
  /// edges can be silhouettes; edges inside a polygon are seen only where it is seen.
  std::vector<bool> on_boundary;
};

/// The scene's polygons (convex ones whole, concave ones triangulated in their plane) with the
/// given exitance per polygon; empty `exitance` means the materials' emission (direct only).
std::vector<EmittingFace> faces_from_polygons(const Scene& scene, std::vector<Rgb> exitance = {});

/// The solution's leaf elements, each radiating its radiosity B. Faces are ordered by polygon
/// (coplanar overlapping polygons: the lower index shows in both gatherers).
std::vector<EmittingFace> faces_from_solution(const Scene& scene, const Solution& solution);

}  // namespace rad
