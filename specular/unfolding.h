#pragma once
/// A chain of apertures unfolded into one scene in which light runs straight (paper 000 §3,
/// §4): the plane mirrors of specular/mirror_images.h and the refracting facets of
/// specular/refraction_images.h are both such chains, differing only in how each leg of the
/// path is mapped (a reflection for a mirror, a depth contraction for a facet, 000 eq. 9).
///
/// A chain of k apertures has k + 1 legs: leg j (0-based) runs up to aperture j (from the
/// receiver for j = 0), leg k beyond the last aperture. Each leg holds the faces inside its
/// half-spaces, clipped to them and mapped by the leg's affine map; the last leg's faces
/// radiate, the others' are black (blockers of the leg). Around each aperture, mapped by the
/// map of the leg beyond it (which agrees on the aperture's plane with the map of the leg
/// before it), a black frame: the "negative polygon" of 000 §3 as opaque pieces reaching past
/// everything a straight line from the receiver can meet. If the maps keep each leg on its
/// side of the apertures, a straight line crosses each aperture's plane once, so a line from
/// the receiver that passes every outline in turn meets each leg's faces only on that leg.
#include <optional>
#include <vector>

#include "geometry/emitting_face.h"
#include "geometry/vec.h"
#include "scene/scene.h"

namespace rad {

/// The side of a plane a leg lies on: height(p) = normal . p - offset > 0.
struct HalfSpace {
  Vec3 normal{0, 0, 1};  ///< Unit
  double offset = 0;
  double height(const Vec3& p) const { return normal.dot(p) - offset; }
};

/// An aperture: a convex outline, counter-clockwise about `normal`, of scene polygon `polygon`.
struct Aperture {
  std::vector<Vec3> outline;
  Vec3 normal{0, 0, 1};
  int polygon = -1;
};

/// A leg: where it lies, and the affine map p -> linear p + translation that places it.
struct Leg {
  std::vector<HalfSpace> bounds;
  Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
  Vec3 translation = Vec3::Zero();
};

/// The unfolded scene: its polygons are the unfolded faces themselves (one per convex source
/// polygon and leg, convex), its materials the scene's (last leg), their black images (the
/// other legs; no mirrors, no refraction: images never reflect or refract) and the frames'.
struct UnfoldedScene {
  Scene scene;
  std::vector<EmittingFace> faces;
  Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();  ///< The receiver x -> linear x...
  Vec3 translation = Vec3::Zero();                       ///< ... + translation
  Rgb specular = Rgb::Ones();  ///< Mirrors: the product of the chain's specular reflectances
  Vec3 receiver(const Vec3& x) const { return linear * x + translation; }
  Vec3 receiver_normal(const Vec3& n) const { return linear * n; }
};

/// Unfolds `faces` (faces of `scene`) along `apertures` and `legs` (#legs = #apertures + 1),
/// with the receiver mapped by (receiver_linear, receiver_translation) (the identity for
/// refraction, T_1 for mirrors). A face within `in_plane` of a bounding plane counts as on it
/// and is left out of that leg. A map need not be an isometry: normals are mapped by its
/// inverse transpose. Faces a map flattens (zero area) are left out.
/// With `crossing_from` (the receiver, for a gather at one point), each leg's image is also
/// clipped to the far side, seen from it, of the image planes of every aperture before the
/// leg: a straight line from the receiver reaches it only by crossing them all. And a face
/// whose image the receiver cannot see through the first aperture is left out: it neither
/// lights nor hides a line that passes the aperture (may_show_through), so the gather is the
/// same over far fewer faces. Where the legs'
/// images overlap (the two sides of a refracting box: in front of the facet a line enters by
/// and of the one it leaves by), a line would otherwise reach the last leg through no
/// aperture at all. Mirror chains keep the legs apart by their construction and pass nothing.
UnfoldedScene unfold_legs(const Scene& scene, const std::vector<EmittingFace>& faces,
                          const std::vector<Aperture>& apertures, const std::vector<Leg>& legs,
                          const Eigen::Matrix3d& receiver_linear, const Vec3& receiver_translation,
                          double in_plane, const std::optional<Vec3>& crossing_from = {});

/// Culling beams (000 §5): false when no line from x through a point of the convex hull of
/// `points` meets the plane of the convex `outline` (its unit normal `normal`, either
/// orientation) inside it: nothing there is seen through it, and nothing there hides what is.
/// Conservative: true whenever the line from x through a point does not meet the plane ahead
/// of x (a point as far from the plane as x, or farther on its side); a margin of 1e-9 of the
/// reach. Cost O(#points log #points + #outline).
bool may_show_through(const std::vector<Vec3>& outline, const Vec3& normal, const Vec3& x,
                      const std::vector<Vec3>& points);

/// `face` clipped to every half-space of `bounds` (|height| <= in_plane counts as on the plane):
/// nothing when no part of it lies strictly inside, or all of it lies in a plane. Each new edge
/// along a plane is marked as a boundary.
std::optional<EmittingFace> clipped_to(const EmittingFace& face,
                                       const std::vector<HalfSpace>& bounds, double in_plane);

}  // namespace rad
