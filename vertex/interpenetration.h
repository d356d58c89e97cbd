#pragma once
/// Where scene polygons pass through each other. Vertex tracing finds the visible map's vertices
/// among polygon vertices and apparent edge crossings (001 §3.1), which assumes polygons meet
/// only at edges; where two polygons interpenetrate, the visible map also has the intersection
/// segment as an edge, with its ends (an edge piercing a face) and its crossings as vertices.
/// These segments do not depend on the viewpoint, so they are computed once per scene.
#include <vector>

#include "scene/scene.h"

namespace rad {

/// The segments along which two non-parallel scene polygons (convex pieces of them) intersect,
/// including contact along a line (a block standing on a floor). Pairs are pruned by bounding
/// boxes (sort and sweep). Segments shorter than 1e-12 of the scene diagonal are dropped.
struct Interpenetration {
  Vec3 a, b;                 ///< The segment's ends.
  int polygon_a, polygon_b;  ///< The two scene polygons.
};
std::vector<Interpenetration> interpenetration_segments(const Scene& scene);

}  // namespace rad
