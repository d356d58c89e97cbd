#pragma once
/// The solution's leaf elements as the faces the exact gatherers take: every element radiates
/// its radiosity B (radiosity reconstruction, 001 §4.2; the local pass, 004 §4).
#include <vector>

#include "geometry/emitting_face.h"
#include "radiosity/solution.h"
#include "scene/scene.h"

namespace rad {

/// One face per leaf element, with the radiosity as exitance. Faces are ordered by polygon
/// (coplanar overlapping polygons: the lower index shows in both gatherers). An element edge
/// lies on its polygon's boundary when both ends are within Scene::tolerance().pad of one
/// polygon edge. Throws Error when an element refers to a polygon the scene does not have.
std::vector<EmittingFace> faces_from_solution(const Scene& scene, const Solution& solution);

}  // namespace rad
