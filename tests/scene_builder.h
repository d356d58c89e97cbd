#pragma once
/// Building small scenes in code for tests: polygons go through the same validation as files.
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
  Scene scene_;
};

}  // namespace rad::test
