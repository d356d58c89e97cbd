#include "scene/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scene/error.h"

namespace rad {
namespace {

double angle_deg(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / std::numbers::pi;
}

CameraSpec cornell_camera() {
  CameraSpec spec;
  spec.eye = {278, 273, -800};
  spec.look_at = {278, 273, 0};
  spec.up = {0, 1, 0};
  spec.fov_deg = 39.3076;
  spec.width = spec.height = 512;
  return spec;
}

TEST(Camera, CentreRayLooksAtTarget) {
  const Camera camera(cornell_camera());
  const Ray r = camera.ray(256, 256);
  EXPECT_EQ(r.origin, Vec3(278, 273, -800));
  EXPECT_NEAR((r.direction - Vec3(0, 0, 1)).norm(), 0, 1e-15);
}

TEST(Camera, EdgeRaysSpanTheFieldOfView) {
  for (double fov : {1.0, 39.3076, 90.0, 150.0}) {
    CameraSpec spec = cornell_camera();
    spec.fov_deg = fov;
    spec.width = 300;  // non-square: the vertical fov is the given one
    spec.height = 200;
    const Camera camera(spec);
    EXPECT_NEAR(angle_deg(camera.ray(150, 0).direction, camera.ray(150, 200).direction), fov, 1e-9);
    // Horizontal: tan(h/2) = aspect * tan(v/2).
    const double h =
        2 * std::atan(1.5 * std::tan(fov * std::numbers::pi / 360)) * 180 / std::numbers::pi;
    EXPECT_NEAR(angle_deg(camera.ray(0, 100).direction, camera.ray(300, 100).direction), h, 1e-9);
  }
}

TEST(Camera, ImageAxesFollowRightAndUp) {
  const Camera camera(cornell_camera());
  // Looking down +z with +y up, image right is -x: the Cornell box's red wall (x = 556) is on
  // the left of the picture.
  EXPECT_LT(camera.ray(511.5, 256).direction.x(), 0);
  EXPECT_GT(camera.ray(0.5, 256).direction.x(), 0);
  // Row 0 is the top.
  EXPECT_GT(camera.ray(256, 0.5).direction.y(), 0);
  for (int y : {0, 100, 511}) {
    for (int x : {0, 300, 511}) {
      EXPECT_NEAR(camera.ray(x + 0.5, y + 0.5).direction.norm(), 1.0, 1e-15);
    }
  }
}

TEST(Camera, RejectsDegenerateSpecs) {
  CameraSpec spec = cornell_camera();
  spec.up = {0, 0, 1};  // parallel to the view direction
  EXPECT_THROW(Camera{spec}, InputError);
  spec = cornell_camera();
  spec.look_at = spec.eye;
  EXPECT_THROW(Camera{spec}, InputError);
  for (double fov : {0.0, -5.0, 180.0, 200.0}) {
    spec = cornell_camera();
    spec.fov_deg = fov;
    EXPECT_THROW(Camera{spec}, InputError) << fov;
  }
  spec = cornell_camera();
  spec.width = 0;
  EXPECT_THROW(Camera{spec}, InputError);
}

}  // namespace
}  // namespace rad
