#pragma once
/// Light refracted through transparent polyhedra by apparent depth contraction (paper 000 §4):
/// seen from x through a facet f (centroid c, normal n) of a medium of relative index eta =
/// n_far / n_near, everything behind f appears moved toward f's plane along n, depths scaled by
/// k = cos / sqrt(eta^2 - 1 + cos^2) (eqs. 7-9), cos taken once, on the line from x to c
/// (§4.2). Polygons stay polygons, so a chain of facets f_1 .. f_k (in at one, out at another)
/// unfolds like a chain of mirrors (specular/unfolding.h): leg j beyond f_j is mapped by
/// M_j = T_1 ... T_j (T_j the contraction at f_j), and the exact gatherers gather the moved
/// sources through the moved outlines at the real x, knowing nothing of refraction.
///
/// A heuristic, as the paper says: one angle per facet, so a source seen through a facet that
/// subtends a wide angle lands in the wrong place; no focusing (caustics). It is kept apart
/// from the certified bound (LocalPassResult::refracted).
///
/// Choices where the paper is silent:
///  - the angle at f_j (j >= 2) is taken on the centroid path, from c_(j-1) to c_j: the path the
///    attenuation is measured along, independent of where x is (the accuracy knob traces the
///    ray from x instead: RefractionPath::traced);
///  - the weight of a chain in channel c is the product over its crossings of what each passes
///    (the transmittance, or the Fresnel transmission at the centroid angle) and of 1 / eta^2
///    (radiance over n^2 is what a crossing keeps: the path tracer shows it is needed, tests/
///    reference/path_tracer_refraction_test.cpp), times exp(-attenuation length) over the legs
///    of the centroid path inside a medium;
///  - total internal reflection at f_j in a channel (eta^2 - 1 + cos^2 <= 0) passes nothing in
///    it, and the light it reflects is not followed (§4.2: "no light through that facet");
///  - one index per channel (§4.3): the channels whose ratios differ get images of their own.
#include <vector>

#include "geometry/emitting_face.h"
#include "scene/scene.h"
#include "specular/unfolding.h"

namespace rad {

/// One convex piece of a refracting polygon (000 §4), as an aperture.
struct RefractingFacet {
  int polygon = -1;
  int object = -1;            ///< Its polygon's object: a chain goes in and out of one object
  std::vector<Vec3> outline;  ///< Convex, counter-clockwise about `normal`
  Vec3 normal{0, 0, 1};       ///< Unit front normal, out of the medium
  double offset = 0;          ///< normal . p = offset on its plane
  Vec3 centroid = Vec3::Zero();
  Refraction refraction;
  double height(const Vec3& p) const { return normal.dot(p) - offset; }
};

/// The convex pieces of the scene's refracting polygons, in polygon order.
std::vector<RefractingFacet> refracting_facets(const Scene& scene);

/// Per facet: the facets of its object when that object is convex (every vertex of the object
/// on or behind every one of its facets' planes, within `in_plane`), else empty. A point is
/// inside a convex object exactly when it is on or behind all of them. Cost O(facets x
/// vertices) per object.
std::vector<std::vector<int>> convex_object_facets(const std::vector<RefractingFacet>& facets,
                                                   double in_plane);

/// A chain of facets crossed on the way from a receiver to the sources: from outside (x in
/// front of the first facet) in at odd positions and out at even ones; from inside (x behind
/// it) out first. Every chain ends outside, where the sources are.
struct RefractionChain {
  std::vector<int> facets;
  bool from_inside = false;
};

/// The chains of at most `depth` crossings: each facet crossed into is followed by a facet of
/// the same object (another one, partly behind it, which it lies partly behind), and each
/// facet crossed out of by a facet partly in front of it (which it lies partly in front of).
std::vector<RefractionChain> refraction_chains(const std::vector<RefractingFacet>& facets,
                                               int depth, double in_plane);

/// What one chain shows x: an unfolded scene and the weight of what it gathers, per channel
/// (0 in the channels it does not carry).
struct RefractedImage {
  UnfoldedScene unfolded;
  Rgb weight = Rgb::Zero();
};

/// The facets of one path, in order (whole facets or pieces of them: facet_pieces), crossed
/// from x, out first when `from_inside`.
struct RefractionPath {
  std::vector<const RefractingFacet*> facets;
  bool from_inside = false;
  /// Beyond the paper (the accuracy knob's paths): the angle at each facet after the first is
  /// that of the ray from x through the first facet's centroid, refracted by Snell's law at each
  /// facet before it in each channel, and the attenuation is measured along that ray, instead
  /// of along the centroid path c_(j-1) -> c_j. Where the facets are far larger than the beam
  /// of light x receives through them (a window pane, a slab), the centroid path runs where
  /// no light goes; along the ray, a slab's two contractions undo each other's angle exactly
  /// (k_1 k_2 = 1) and leave the ray's lateral offset, so splitting the first facet converges.
  bool traced = false;
};

/// The images of `path` at x (000 eqs. 7-9 at the centroid angles): one for all channels, or
/// one per group of channels with the same indices; none in a channel past a critical angle,
/// or when a facet of the path is seen edge-on. `faces` are what radiates and hides.
std::vector<RefractedImage> refracted_images(const Scene& scene,
                                             const std::vector<EmittingFace>& faces,
                                             const RefractionPath& path, const Vec3& x,
                                             double in_plane);
/// The same for a chain of whole facets.
std::vector<RefractedImage> refracted_images(const Scene& scene,
                                             const std::vector<EmittingFace>& faces,
                                             const std::vector<RefractingFacet>& facets,
                                             const RefractionChain& chain, const Vec3& x,
                                             double in_plane);

/// Culling beams (000 §5) for a path under construction: false when the image of its last
/// facet, seen from x, lies outside the image of an earlier one in every channel, so that no
/// line from x passes through them all. Conservative. Cost O(#facets^2) per distinct index.
bool may_pass(const RefractionPath& path, const Vec3& x);

/// Beyond the paper, the accuracy knob: the heuristic takes one angle per facet, which is
/// right where the depth ratio k hardly varies over the facet as seen from `viewpoint`. Splits
/// `facet` in two (through its centroid, across its longest extent), widest spread first, until
/// over each piece max |k(v) - k(c)| / k(c) <= `tolerance` at its vertices v in every channel (a
/// piece partly past the critical angle counts as infinitely spread; a channel the facet passes
/// nothing of is not looked at) or there are `max_pieces`.
/// Each piece keeps the facet's plane, material and object. An infinite tolerance keeps the facet
/// whole (the paper's method).
///
/// With `beyond` (the facets of the chain after this one), the spread is that of the ratios
/// at every facet of the chain along the traced rays (RefractionPath::traced) from the
/// viewpoint through the piece's corners, against the ray through its centroid: the knob then
/// splits only the first facet of a chain and converges on the traced path.
std::vector<RefractingFacet> facet_pieces(const RefractingFacet& facet, const Vec3& viewpoint,
                                          bool entering, double tolerance, int max_pieces,
                                          const std::vector<const RefractingFacet*>& beyond = {});

}  // namespace rad
