#pragma once
/// Module `scene` (rad_scene): the scene model (materials, planar polygons, an optional camera,
/// and what loading noticed), scene files (scene_loader.h: JSON read by scene_json.h, with
/// OBJ/PLY/OFF/STL meshes, mesh_reader.h) and their validation, the input files a command read
/// (input_files.h: regular files only, recorded so no output overwrites them), the camera, ray
/// casting (Embree behind ray_caster.h), the polygons as gatherer faces (polygon_faces.h), the
/// mirror pieces and their chains (mirror_pieces.h), whether a refracting object is a closed solid
/// (closed_surface.h), and point lights (point_light.h) with what reaches a point straight from
/// them and their glossy highlights (point_lights.h).
///
/// May use: geometry, Embree (in .cpp files only), nlohmann-json.
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "geometry/tolerance.h"
#include "scene/camera.h"
#include "scene/material.h"
#include "scene/point_light.h"
#include "scene/polygon.h"

namespace rad {

/// One entry of the scene file's "objects" list, kept for messages and statistics.
struct SceneObject {
  std::string name;       ///< "name" from the file, or empty.
  std::string mesh;       ///< Mesh path as written, or empty for inline polygons.
  int material = -1;      ///< Index into Scene::materials; -1 when its faces have several.
  int first_polygon = 0;  ///< Its polygons are [first_polygon, first_polygon + polygon_count).
  int polygon_count = 0;
};

/// Axis-aligned box; empty (lo > hi) until a point is added.
struct Bounds {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
  void add(const Vec3& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); }
  double diagonal() const { return (hi - lo).norm(); }
};

/// A loaded, validated scene: every polygon is planar, simple, of non-zero area, with finite
/// coordinates and a valid material.
struct Scene {
  std::filesystem::path path;  ///< The scene file it came from (empty if built in code).
  std::vector<Material> materials;
  std::vector<SceneObject> objects;
  std::vector<Polygon> polygons;
  std::vector<PointLight> lights;  ///< "lights" in the file: isotropic point lights
  std::optional<CameraSpec> camera;
  /// Longest chain of plane-mirror reflections the solver, the local pass and the eye follow
  /// (000 §3; "mirror_depth" in the file, 0 to 8).
  static constexpr int kDefaultMirrorDepth = 2;
  int mirror_depth = kDefaultMirrorDepth;
  /// Most crossings of refracting interfaces a path follows (000 §4: the facets of a chain;
  /// "refraction_depth" in the file, 0 to 8). 2 sees through a convex block (in, then out).
  static constexpr int kDefaultRefractionDepth = 2;
  int refraction_depth = kDefaultRefractionDepth;
  std::vector<std::string> warnings;  ///< Things loading fixed or noticed, one line each.

  /// "objects[2] \"tall block\" polygon 5" (plus " triangle 1" for a split polygon).
  std::string describe_polygon(int polygon) const;
  Bounds bounds() const;
  /// The tolerance policy every gatherer and the culling use (geometry/tolerance.h), from the
  /// diagonal of bounds().
  Tolerance tolerance() const { return Tolerance::for_scene_size(bounds().diagonal()); }
  double total_area() const;
  /// Sum of emission * area over polygons: emitted power in W when lengths are metres.
  Rgb emitted_power() const;
  /// Sum of 4 pi intensity over the point lights: their power in W.
  Rgb light_power() const;
  int emitter_count() const;
  int vertex_count() const;
  /// 64-bit FNV-1a hash (16 hex digits) of every polygon's vertices and material values: a
  /// solution records it so it is never applied to a different scene.
  std::string fingerprint() const;
};

}  // namespace rad
