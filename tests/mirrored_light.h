#pragma once
/// A point light beside a perfect plane mirror over a floor, and the closed form of the floor's
/// irradiance by the image method (000 §3) written out by hand: the light's image through the
/// mirror plane x = 1.5 is L' = (3 - L.x, L.y, L.z), seen where the line from the floor point to
/// L' crosses the mirror's rectangle. Shared by the tests of the local pass, the path tracer,
/// the Monte Carlo gather and the solver, none of which it uses.
#include <cmath>

#include "tests/scene_builder.h"

namespace rad::test {

struct MirroredLight {
  static constexpr double kSpecular = 0.7;
  Vec3 light{0.3, -0.2, 2};
  Rgb intensity{1, 2, 3};
  Scene scene;

  /// The floor [-5, 1.5] x [-5, 5] (reflectance rho, facing up), the mirror on x = 1.5,
  /// y in [-1, 1], z in [0, 2.5], facing the light (specular kSpecular, black otherwise).
  explicit MirroredLight(const Rgb& rho = Rgb::Zero()) {
    SceneBuilder b;
    b.rectangle(-5, 1.5, -5, 5, 0, false, b.material("floor", rho, Rgb::Zero()));
    const int mirror =
        b.material("mirror", Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Constant(kSpecular));
    b.polygon({{1.5, -1, 0}, {1.5, -1, 2.5}, {1.5, 1, 2.5}, {1.5, 1, 0}}, mirror);
    b.scene().lights.push_back({light, intensity});
    scene = b.scene();
  }

  /// I cos / r^2 straight from the light at the floor point (x, y, 0).
  Rgb straight(double x, double y) const {
    const Vec3 to = light - Vec3(x, y, 0);
    return intensity * (to.z() / std::pow(to.norm(), 3));
  }

  /// The same from the image, times the mirror's specular, where the line meets the mirror.
  Rgb reflected(double x, double y) const {
    const Vec3 image(3 - light.x(), light.y(), light.z());
    const Vec3 p(x, y, 0), to = image - p;
    const Vec3 crossing = p + to * ((1.5 - x) / to.x());
    if (!(std::abs(crossing.y()) < 1 && crossing.z() > 0 && crossing.z() < 2.5)) return Rgb::Zero();
    return kSpecular * intensity * (to.z() / std::pow(to.norm(), 3));
  }

  Rgb expected(double x, double y) const { return straight(x, y) + reflected(x, y); }
};

}  // namespace rad::test
