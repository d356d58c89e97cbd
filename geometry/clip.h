#pragma once
/// Clipping a polygon to a half-space (Sutherland-Hodgman), written once for every caller: the
/// horizon clip before Lambert's formula and before projection onto the hemisphere, Stark's
/// horizon clip, vertex tracing's image square, and the shaft's planes.
#include <cstddef>
#include <vector>

#include "geometry/vec.h"

namespace rad {

/// Marks an output vertex whose outgoing edge runs along the clipping plane (see clip_loop).
inline constexpr int kEdgeAlongCut = -1;

/// The crossing of the segment a -> b with the plane, from the signed distances da and db of
/// its ends (of opposite signs): a + da / (da - db) (b - a). Computed from a, so the point lies
/// on the kept side's segment.
inline Vec3 interpolated_crossing(const Vec3& a, const Vec3& b, double da, double db) {
  return a + (da / (da - db)) * (b - a);
}

/// One Sutherland-Hodgman pass over the closed loop `loop[0..count)`: keeps the part where
/// `distance(p) >= 0`. Calls `emit(point, edge)` for each vertex of the result, in order, where
/// `edge` says on which input edge the vertex's outgoing edge lies (edge i joins loop[i] and
/// loop[i+1]), or kEdgeAlongCut when it runs along the plane. Vertices on the plane are kept;
/// a crossing is made only where an edge passes strictly from one side to the other, so no
/// vertex is repeated. `crossing(a, b, da, db)` places it (interpolated_crossing, or a caller's
/// more exact construction). The result may have fewer than 3 vertices. Cost O(count).
template <typename Loop, typename Distance, typename Crossing, typename Emit>
void clip_loop(const Loop& loop, size_t count, const Distance& distance, const Crossing& crossing,
               const Emit& emit) {
  for (size_t i = 0; i < count; ++i) {
    const Vec3& a = loop[i];
    const Vec3& b = loop[(i + 1) % count];
    const double da = distance(a), db = distance(b);
    const int edge = static_cast<int>(i);
    if (da >= 0) emit(a, da == 0 && db < 0 ? kEdgeAlongCut : edge);
    if ((da > 0 && db < 0) || (da < 0 && db > 0))
      emit(crossing(a, b, da, db), da > 0 ? kEdgeAlongCut : edge);
  }
}

/// Clips a planar polygon to the half-space n . (p - point) >= 0 (one pass of clip_loop, exact
/// in 3D, before any projection). Vertices on the plane are kept. Returns the clipped polygon
/// (possibly empty; possibly with fewer than 3 vertices).
inline std::vector<Vec3> clip_to_halfspace(const std::vector<Vec3>& polygon, const Vec3& point,
                                           const Vec3& n) {
  std::vector<Vec3> out;
  out.reserve(polygon.size() + 2);
  clip_loop(
      polygon, polygon.size(), [&](const Vec3& p) { return n.dot(p - point); },
      interpolated_crossing, [&](const Vec3& p, int) { out.push_back(p); });
  return out;
}

}  // namespace rad
