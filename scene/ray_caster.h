#pragma once
/// Closest-hit and occlusion queries against a scene's polygons. Embree does the traversal in
/// single precision; the reported distance and point are recomputed in double against the hit
/// polygon's plane. Embree's headers stay inside ray_caster.cpp.
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "scene/ray.h"
#include "scene/scene.h"

namespace rad {

/// A ray's first intersection with the scene.
struct Hit {
  int polygon = -1;           ///< Index into Scene::polygons.
  double distance = 0;        ///< Along the (unit) ray direction, in scene units.
  Vec3 point;                 ///< origin + distance * direction.
  Vec3 normal;                ///< The polygon's unit front normal (not flipped).
  bool front_facing = false;  ///< True when the ray arrives at the front side.
  Vec3 direction;             ///< The (unit) direction of the ray that met it.
};

/// Ray queries against every polygon of a scene, both sides (polygons are opaque from both).
/// Built once (O(n log n)); queries are thread-safe and may run concurrently. The scene must
/// outlive the caster.
class RayCaster {
 public:
  explicit RayCaster(const Scene& scene);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  /// The closest hit with t in [t_min, t_max], or nothing.
  std::optional<Hit> closest_hit(const Ray& ray, double t_min = 0,
                                 double t_max = std::numeric_limits<double>::infinity()) const;

  /// True when any polygon intersects the ray with t in [t_min, t_max].
  bool occluded(const Ray& ray, double t_min, double t_max) const;

  /// A ray over t in [t_min, t_max], for the queries of many rays at once.
  struct Segment {
    Ray ray;
    double t_min, t_max;
  };
  /// occluded() of each segment, as one coherent stream (Embree's rtcOccluded1M traces rays
  /// that share an origin as packets): blocked[i] is 1 when some polygon meets segment i. The
  /// answers are occluded()'s.
  void occluded(const std::vector<Segment>& segments, std::vector<char>& blocked) const;

  /// What passes along the ray over t in [t_min, t_max], per channel: the product of the
  /// transmittances of the polygons it crosses (filters, 000 §2.2), 0 at the first opaque one,
  /// 1 when it crosses none. Without filters in the scene this is one occlusion query. Two
  /// crossings closer than `gap` are taken as one surface (rays through a shared edge).
  Rgb transmittance(const Ray& ray, double t_min, double t_max, double gap) const;
  /// True when some polygon's material is a filter.
  bool has_filters() const { return has_filters_; }

  /// How many bends RayCaster::follow takes along one path.
  struct Bends {
    int reflections = 0;  ///< Off the fronts of plane mirrors (000 §3)
    int refractions = 0;  ///< Crossings of refracting interfaces, and their reflections (§4)
    /// As a limit: false follows only the refracted rays at interfaces, dropping what they
    /// reflect (Fresnel, total internal reflection): the model of 000 §4's heuristic.
    bool interface_reflections = true;
    /// As a limit: false leaves glossy surfaces (Material::gloss > 0) unreflected and roughened
    /// panes unpassed, for a caller that samples their lobes itself (the path tracer); true
    /// takes each lobe's centre: reflects glossy mirrors about it, as mirrors, and passes
    /// roughened panes straight on, as filters of their glossy transmittance (the eye rays,
    /// the Monte Carlo gather; the solver carries a pane the same way).
    bool glossy_as_mirror = true;
  };
  /// The scene's limits: mirror_depth and refraction_depth.
  static Bends limits_of(const Scene& scene) {
    return {scene.mirror_depth, scene.refraction_depth};
  }

  /// Follows a ray through filters (on, times the transmittance: 000 §2.2), off the fronts of
  /// mirrors (reflected, times the specular reflectance: 000 §3) and across refracting
  /// interfaces (000 §4), calling visit(hit, weight, bends) for each surface met, weight the
  /// product of what the filters, mirrors and interfaces before it passed on, bends how many
  /// mirrors and interfaces lie on the way. At most `limits` of each along a path.
  /// A refracting interface splits the path in two, each followed exactly:
  ///  - the refracted ray (Snell, 000 eq. 6), times the interface's transmittance (or the
  ///    Fresnel transmission) and times 1 / eta^2, eta = n_far / n_near: radiance over n^2 is
  ///    what a crossing keeps, and this follows light backwards; a dispersive interface splits
  ///    it into one ray per channel (§4.3);
  ///  - the reflected ray, times the Fresnel reflection (with "fresnel") or 1 in the channels
  ///    past the critical angle (total internal reflection, either way).
  /// Inside (after crossing into a front, until crossing out of one) the weight falls as
  /// exp(-attenuation length). A path that starts inside a refracting object is not known to
  /// be inside: no attenuation on its first leg.
  /// Ends at opaque surfaces and misses. Hits closer than `gap` to the previous one are the
  /// same surface. Surfaces met within `near` of the ray's origin on its first leg are passed
  /// through: for a ray started a little off its receiver point (along the normal, and back
  /// along the ray, so that it never starts inside a plane), they are polygons whose plane
  /// holds the point (an edge, a wall's foot), which the exact gatherers see edge-on: no solid
  /// angle, no occlusion. Without filters, mirrors and refraction: the first hit alone, with
  /// weight 1.
  void follow(const Ray& ray, Bends limits, double gap,
              const std::function<void(const Hit&, const Rgb&, int)>& visit, double near = 0) const;

  const Scene& scene() const { return scene_; }

 private:
  struct Impl;
  const Scene& scene_;
  bool has_filters_ = false;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rad
