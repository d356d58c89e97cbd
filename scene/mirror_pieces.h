#pragma once
/// Plane mirrors as the scene has them (paper 000 §3): the convex pieces of its mirror polygons
/// and the chains of reflections between them worth following. The local pass unfolds each
/// chain (specular/mirror_images.h); the solver shoots through them (radiosity/solver.cpp).
#include <vector>

#include "geometry/refraction.h"
#include "geometry/vec.h"
#include "scene/scene.h"

namespace rad {

/// One convex piece of a mirror polygon, as an aperture.
struct MirrorPiece {
  int polygon = -1;           ///< The scene polygon it is part of (in the scene it came from).
  std::vector<Vec3> outline;  ///< Convex, counter-clockwise about `normal`.
  Vec3 normal{0, 0, 1};       ///< Unit front normal: the mirror reflects on this side only.
  double offset = 0;          ///< The plane normal . p = offset.
  Rgb specular = Rgb::Zero();

  double height(const Vec3& p) const { return normal.dot(p) - offset; }
  Vec3 reflect(const Vec3& p) const { return p - 2 * height(p) * normal; }
  Vec3 reflect_direction(const Vec3& d) const { return rad::reflect(d, normal); }
  /// True when p (in the piece's plane) lies in its outline (its edges included).
  bool contains(const Vec3& p) const {
    const size_t k = outline.size();
    for (size_t i = 0; i < k; ++i) {
      const Vec3& a = outline[i];
      const Vec3& b = outline[(i + 1) % k];
      if ((b - a).cross(p - a).dot(normal) < 0) return false;
    }
    return true;
  }
};

/// The convex pieces of the scene's mirror polygons (material specular > 0; concave ones as
/// triangles), in polygon order.
std::vector<MirrorPiece> mirror_pieces(const Scene& scene);

/// The chains of mirror pieces of at most `depth` reflections worth unfolding: no piece after
/// itself or after a piece in its plane, and each next piece partly in front of the one before
/// (and that one partly in front of it), in lexicographic order of piece indices.
std::vector<std::vector<int>> mirror_chains(const std::vector<MirrorPiece>& pieces, int depth,
                                            double in_plane);

}  // namespace rad
