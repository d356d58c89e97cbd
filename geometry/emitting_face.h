#pragma once
/// What the exact gatherers see: convex planar faces, each a piece of one scene polygon, with
/// the exitance it radiates from its front. Direct lighting uses the polygons themselves
/// (concave ones as triangles: scene/polygon_faces.h); radiosity reconstruction uses the
/// solution's leaf elements, so that every patch emits its own radiosity (001 §4.2;
/// radiosity/solution_faces.h). Both exact methods take the same faces, so they can be compared
/// face for face.
#include <vector>

#include "geometry/vec.h"

namespace rad {

struct EmittingFace {
  int polygon =
      -1;  ///< The scene polygon it is part of (an id: coplanar order, same-polygon tests).
  std::vector<Vec3> vertices;  ///< Convex, counter-clockwise about `normal`.
  Rgb exitance = Rgb::Zero();  ///< Radiated from the front side only [W/m^2].
  /// Per edge i (vertices i -> i+1): true when it lies on the polygon's boundary. Only such
  /// edges can be silhouettes; edges inside a polygon are seen only where it is seen.
  std::vector<bool> on_boundary;
  Vec3 normal{0, 0, 1};  ///< The polygon's unit front normal (its plane's).
  /// Fraction of light passing straight through, from either side (a filter, 000 §2.2): what
  /// lies behind it along a line of sight reaches x multiplied by it. 0: an opaque occluder.
  Rgb transmittance = Rgb::Zero();
};

}  // namespace rad
