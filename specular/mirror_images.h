#pragma once
/// Plane mirrors by the mirrored receiver (paper 000 §3, Fig. 3b-c): the irradiance a plane
/// mirror reflects onto x is its specular reflectance times the irradiance at x' (x mirrored in
/// the mirror's plane, with the normal mirrored) from what shows through the mirror's outline,
/// with the blockers of both legs. The paper traces each vertex twice, from x and from x', and
/// clips by the "negative polygon" (the complement of the mirror in its plane); chains of
/// mirrors are traced "separately ... with the source and other blockers reflected through all
/// but this surface". Here each chain m_1 .. m_k (x -> m_1 -> ... -> m_k -> what shows) is
/// unfolded once into a scene of its own, in which the light path is a straight line from
/// x^(k) = T_1(x), T_j = R_k ... R_j (R_j the reflection in m_j's plane):
///  - the last leg (from m_k on): the faces in front of m_k, clipped to it, radiating as in the
///    scene;
///  - leg j < k + 1 (from m_(j-1) to m_j; from x for j = 1): the faces in front of both planes,
///    clipped to them, mapped by T_j, black (blockers between two reflections);
///  - at each m_j, its outline mapped by T_(j+1) with a black frame around it in that plane:
///    the negative polygon as opaque positive pieces, reaching past everything the straight
///    line can meet.
/// A straight line crosses each plane once, so a path through every outline in turn is a
/// reflected path, and each leg meets only its own blockers. Every exact gatherer, and the
/// local pass with its certified bound, then gathers at x^(k) knowing nothing of mirrors.
/// Filters keep their transmittance on every leg, so mirrors seen through filters and filters
/// seen in mirrors compose.
#include <optional>
#include <vector>

#include "geometry/emitting_face.h"
#include "geometry/vec.h"
#include "scene/mirror_pieces.h"
#include "scene/scene.h"
#include "specular/unfolding.h"

namespace rad {

/// Unfolds `faces` (faces of `scene`) along the chain of `pieces` (specular/unfolding.h): its
/// receiver map is T_1, its `specular` the product of the chain's specular reflectances. Faces
/// within `in_plane` of a plane count as on it: a leg bounded by that plane leaves them out (the
/// mirror covers them, or they are seen edge-on). The frames reach from each outline to past the
/// farthest point of the unfolded legs, which hold every mirrored receiver.
UnfoldedScene unfold(const Scene& scene, const std::vector<EmittingFace>& faces,
                     const std::vector<MirrorPiece>& pieces, const std::vector<int>& chain,
                     double in_plane);

/// The box of what can send light to x' through `mirror`'s outline: the faces in front of it
/// that radiate, the point lights in front of it, and the mirror pieces there (reflected
/// light); empty when there is none.
Eigen::AlignedBox3d sources_in_front(const std::vector<EmittingFace>& faces,
                                     const std::vector<MirrorPiece>& pieces,
                                     const std::vector<PointLight>& lights,
                                     const MirrorPiece& mirror, double in_plane);

/// Culling beams (000 §5): false when no segment from the mirrored receiver x' (behind the
/// plane) to a point of `sources` passes through the outline, so that nothing reaches x
/// through this mirror. Conservative: the box's corners are projected from x' onto the plane
/// and their convex hull tested against the outline (with a margin); true whenever a corner
/// does not lie in front of the plane. Cost O(1).
bool may_see_through(const MirrorPiece& mirror, const Vec3& x_mirrored,
                     const Eigen::AlignedBox3d& sources);

}  // namespace rad
