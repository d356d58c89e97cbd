#pragma once
/// Building small scenes in code for tests: polygons go through the same validation as files.
#include <algorithm>
#include <string>
#include <vector>

#include "scene/polygon_validation.h"
#include "scene/scene.h"

namespace rad::test {

class SceneBuilder {
 public:
  /// Adds a material and returns its index.
  int material(const std::string& name, const Rgb& reflectance, const Rgb& emission) {
    scene_.materials.push_back(Material{name, reflectance, emission});
    return static_cast<int>(scene_.materials.size()) - 1;
  }
  /// Adds a filter or mirror material (000 §2.2, §3) and returns its index.
  int material(const std::string& name, const Rgb& reflectance, const Rgb& emission,
               const Rgb& transmittance, const Rgb& specular = Rgb::Zero()) {
    scene_.materials.push_back(Material{name, reflectance, emission, transmittance, specular});
    return static_cast<int>(scene_.materials.size()) - 1;
  }
  /// Adds the interface of a refracting polyhedron (000 §4), black otherwise.
  int material(const std::string& name, const Refraction& refraction) {
    Material m{name, Rgb::Zero(), Rgb::Zero()};
    m.refraction = refraction;
    scene_.materials.push_back(m);
    return static_cast<int>(scene_.materials.size()) - 1;
  }
  /// An axis-aligned box [lo, hi], its six faces' fronts facing out: one object.
  void box(const Vec3& lo, const Vec3& hi, int material) { add_box(lo, hi, material, false); }
  /// A closed room [lo, hi]: the box's six faces with their fronts facing in, one object.
  void room(const Vec3& lo, const Vec3& hi, int material) { add_box(lo, hi, material, true); }
  /// Adds a polygon (counter-clockwise from its front) and returns its index.
  int polygon(std::vector<Vec3> vertices, int material) {
    const int object = static_cast<int>(scene_.objects.size());
    std::vector<std::string> warnings;
    const int first = static_cast<int>(scene_.polygons.size());
    for (Polygon& p :
         make_polygons(std::move(vertices), "test polygon", material, object, 0, warnings)) {
      scene_.polygons.push_back(std::move(p));
    }
    scene_.objects.push_back(
        SceneObject{"", "", material, first, static_cast<int>(scene_.polygons.size()) - first});
    return first;
  }
  /// An axis-aligned rectangle [x0, x1] x [y0, y1] at height z, front facing -z (down) or +z.
  int rectangle(double x0, double x1, double y0, double y1, double z, bool facing_down,
                int material) {
    if (facing_down) return polygon({{x0, y0, z}, {x0, y1, z}, {x1, y1, z}, {x1, y0, z}}, material);
    return polygon({{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, material);
  }
  const Scene& scene() const { return scene_; }
  Scene& scene() { return scene_; }

 private:
  void add_box(const Vec3& lo, const Vec3& hi, int material, bool facing_in) {
    // Corner k has x = hi where bit 0 of k is set, y where bit 1 is, z where bit 2 is; each
    // face counter-clockwise seen from outside.
    const auto corner = [&](int k) {
      return Vec3(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
    };
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    const int first = static_cast<int>(scene_.polygons.size());
    const int object = static_cast<int>(scene_.objects.size());
    for (const auto& f : faces) {
      std::vector<Vec3> face{corner(f[0]), corner(f[1]), corner(f[2]), corner(f[3])};
      if (facing_in) std::reverse(face.begin(), face.end());
      polygon(std::move(face), material);
    }
    scene_.objects.resize(object + 1);
    scene_.objects[object].polygon_count = static_cast<int>(scene_.polygons.size()) - first;
    for (int p = first; p < static_cast<int>(scene_.polygons.size()); ++p)
      scene_.polygons[p].object = object;
  }

  Scene scene_;
};

}  // namespace rad::test
