#pragma once
/// The scene's polygons as the faces the exact gatherers take (geometry/emitting_face.h).
#include <vector>

#include "geometry/emitting_face.h"
#include "scene/scene.h"

namespace rad {

/// The scene's polygons (convex ones whole, concave ones triangulated in their plane) with the
/// given exitance per polygon; empty `exitance` means the materials' emission (direct only).
/// Throws Error when `exitance` has the wrong size.
std::vector<EmittingFace> faces_from_polygons(const Scene& scene, std::vector<Rgb> exitance = {});

/// Makes the face counter-clockwise about its normal (triangulation and element corners may
/// come either way round); edge flags follow their edges.
void orient_counter_clockwise(EmittingFace& face);

}  // namespace rad
