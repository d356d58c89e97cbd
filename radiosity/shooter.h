#pragma once
/// What a shot delivers to one receiver point: the form factor from the point to a shooting
/// patch times what passes along the shadow rays, directly and by way of the mirrors' images.
#include <tbb/enumerable_thread_specific.h>

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "radiosity/shadow_culling.h"
#include "radiosity/solution.h"
#include "scene/mirror_pieces.h"
#include "scene/point_lights.h"
#include "scene/ray_caster.h"

namespace rad {

struct Sphere {
  Vec3 centre;
  double radius;
};
/// The sphere about `centre` through the farthest of `corners`.
Sphere bounding_sphere(const std::vector<Vec3>& corners, const Vec3& centre);

/// An upper bound on the form factor from any point x of a planar receiver (inside the sphere
/// `receiver`, in the plane through receiver.centre with unit normal `normal`) to anything
/// inside the sphere `source`, seen or hidden. Every direction that reaches the source from x
/// lies in the cone of half-angle a_x about it, sin a_x = r / d_x (r its radius, d_x the
/// distance of its centre c), and d_x >= D = |c - receiver.centre| - receiver.radius. So:
///  - the cone's projected solid angle is at most pi sin^2 a_x (its largest, about the
///    normal): F <= (r / D)^2;
///  - along each of those directions the first point y met on the sphere lies at most h + r
///    above the plane (h = normal . (c - receiver.centre), the same for every x of the plane)
///    and at least D - r from x, so its cosine is at most (h + r) / (D - r), and the cone's
///    solid angle is 2 pi (1 - cos a_x) <= 2 pi (1 - cos a_D): F <= 2 (1 - cos a_D)
///    min(1, (h + r) / (D - r)), and 0 when h + r <= 0 (the source lies behind the plane).
/// The smaller of the two. 1 when the spheres meet (D - r <= 0). For a source low over the
/// receiver's horizon, the second is the tighter: on the IFC house's coarse hierarchical
/// solve it took the point-patch pairs from 9.43 to 9.03 million.
double sphere_form_factor_bound(const Sphere& receiver, const Vec3& normal, const Sphere& source);

/// A point of a patch at parametric (u, v) in [0, 1]^2: bilinear on quads; on triangles the
/// square is folded onto the triangle (area-preserving up to the fold).
Vec3 patch_point(const Patch& p, double u, double v);

/// Lambert's form factor from x (unit normal n) to the convex polygon `corners` of unit normal
/// `normal`, with nothing between, where x is in front of the polygon; 0 behind it.
double unblocked_form_factor(const Vec3& x, const Vec3& n, const std::vector<Vec3>& corners,
                             const Vec3& normal);

class Shooter {
 public:
  /// `epsilon`: surfaces this close to either end of a shadow ray are not counted.
  Shooter(const RayCaster& caster, const SolverSettings& settings, double epsilon);

  /// Form factor from a receiver point (on polygon `polygon`) to the patch, times the mean
  /// over the shadow rays of what passes along each (0 or 1 through opaque polygons, the
  /// product of the transmittances through filters, 000 §2.2), per channel; plus the same
  /// from the patch's images in every chain of mirrors (000 §3: the image method), times the
  /// chain's specular reflectance. `key` selects the jitter stream; `fewer` divides the side
  /// of the square of shadow rays (at least one ray).
  Rgb visible_form_factor(const Vec3& x, const Vec3& n, int polygon, const Patch& shooter,
                          uint64_t key, int fewer = 1) const;

  /// The irradiance at x (unit normal n) from the scene's point lights, straight and by their
  /// images in the mirrors (scene/point_lights.h), the shadow rays offset by epsilon like the
  /// patches'.
  Rgb point_light_irradiance(const Vec3& x, const Vec3& n) const;

  /// True when the point x (normal n) lies inside a closed object: every probe ray from just
  /// above it meets the back of a polygon. Such points (a floor under a block standing on it)
  /// neither receive nor radiate.
  bool is_buried(const Vec3& x, const Vec3& n) const;

  /// True when a probe ray from x (normal n) meets the front of a polygon closer than
  /// `distance`: x lies near a concave junction or a contact.
  bool faces_within(const Vec3& x, const Vec3& n, double distance) const;

  /// True when a polygon other than the receiver's and the shooter's crosses the segment from
  /// x to the shooter's centre: one ray, which ShadowCulling::may_be_hidden asks for before it
  /// builds a shaft (its `on_the_way`).
  /// `blocker`, when given, is set to the polygon the ray meets (-1 when none).
  bool something_on_the_way(const Vec3& x, int polygon, const Patch& shooter,
                            int* blocker = nullptr) const;

  /// True when polygon `blocker` alone hides the whole of the shooter from x, so that every
  /// shadow ray would be blocked and the visible fraction is exactly 0 without casting one
  /// (hides_between() from the one point x to the shooter's corners). A wall between two rooms
  /// hides most pairs of a building this way, and the rays were most of its solve.
  bool hides_all(const Vec3& x, const Patch& shooter, int blocker) const;
  /// True when polygon `blocker` alone hides every point of the hull of `to` from every point
  /// of the hull of `from`: the blocker is opaque and convex, its plane has every point of
  /// `from` on one side and every point of `to` on the other (each by more than epsilon), and
  /// the segment from each point of `from` to each of `to` crosses it more than epsilon inside
  /// its edges. Proof: for a fixed end b in hull(to), the segments from the points of
  /// hull(from) meet the blocker's plane in the hull of their crossings from `from`'s points
  /// (a central projection from b, defined on all of them since the plane separates b from
  /// each, maps segments to segments and so a hull to the hull of the images); the crossing
  /// from a point a of `from` to b lies, by the same argument from a, in the hull of a's
  /// crossings to `to`'s points. So every crossing lies in the hull of the crossings of the
  /// pairs of points, inside the convex blocker inset by epsilon, as those are. Each shadow
  /// ray between the two hulls then meets the blocker's interior, farther than epsilon from
  /// both of its ends, where the caster's watertight test finds it.
  bool hides_between(std::span<const Vec3> from, std::span<const Vec3> to, int blocker) const;

  /// Whether the scene has mirror chains whose images a receiver may see the shooter in (then
  /// a receiver behind the shooter's plane can still receive from it).
  bool sees_images() const { return !chains_.empty(); }

  /// Pairs asked about, those no polygon could hide, and those one polygon hides whole (both
  /// without rays).
  struct PairCounts {
    long long pairs = 0, unhidden = 0, hidden = 0;
  };
  PairCounts counts() const;

 private:
  Rgb image_form_factor(const Vec3& x, const Vec3& n, const Patch& shooter,
                        const std::vector<int>& chain, uint64_t key, int side) const;
  template <typename Visit>
  void for_each_sample(const Patch& shooter, uint64_t key, int side, const Visit& visit) const;
  template <typename Pass>
  Rgb mean_over_samples(const Patch& shooter, uint64_t key, int side, const Pass& pass) const;
  std::optional<RayCaster::Segment> leg_segment(const Vec3& a, const Vec3& b) const;
  Rgb leg(const Vec3& a, const Vec3& b) const;
  double visible_fraction(const Vec3& x, const Patch& shooter, uint64_t key, int side) const;
  Rgb direct_form_factor(const Vec3& x, const Vec3& n, int polygon, const Patch& shooter,
                         uint64_t key, int side) const;

  const RayCaster& caster_;
  ShadowCulling culling_;
  double epsilon_;
  bool cull_ = true;
  /// The pairs' counts, per thread: one atomic counter that both threads added to at every
  /// pair (14 million on the Cornell box) cost an eighth of the demo's solve in cache-line
  /// traffic. Cache-aligned per thread (tbb's default allocator), summed by counts().
  mutable tbb::enumerable_thread_specific<PairCounts> counts_;
  int side_ = 4;
  uint64_t seed_ = 1;
  double in_plane_ = 0;
  /// Per scene polygon: opaque (no filter, no refraction) and convex, a candidate for
  /// hides_all().
  std::vector<char> solid_convex_;
  std::vector<MirrorPiece> pieces_;
  std::vector<std::vector<int>> chains_;  ///< Of at most Scene::mirror_depth reflections
  PointLightIrradiance lights_;
};

}  // namespace rad
