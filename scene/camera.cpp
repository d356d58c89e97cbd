#include "scene/camera.h"

#include <cmath>
#include <numbers>
#include <string>

#include "geometry/tolerance.h"
#include "scene/error.h"

namespace rad {

Camera::Camera(const CameraSpec& spec) : spec_(spec) {
  if (!(spec.fov_deg > 0 && spec.fov_deg < 180)) {
    throw InputError("camera: fov_deg must be in (0, 180), got " + std::to_string(spec.fov_deg));
  }
  if (spec.width <= 0 || spec.height <= 0) {
    throw InputError("camera: width and height must be positive, got " +
                     std::to_string(spec.width) + " x " + std::to_string(spec.height));
  }
  const Vec3 view = spec.look_at - spec.eye;
  if (!(view.norm() > 0)) throw InputError("camera: eye and look_at coincide");
  forward_ = view.normalized();
  const Vec3 side = forward_.cross(spec.up);
  if (!(side.norm() > relative::kMatch * spec.up.norm())) {
    throw InputError("camera: up is zero or parallel to the view direction");
  }
  right_ = side.normalized();
  up_ = right_.cross(forward_);
  tan_half_fov_ = std::tan(0.5 * spec.fov_deg * std::numbers::pi / 180.0);
}

Ray Camera::ray(double x, double y) const {
  const double aspect = static_cast<double>(spec_.width) / spec_.height;
  const double sx = (2.0 * x / spec_.width - 1.0) * tan_half_fov_ * aspect;
  const double sy = (1.0 - 2.0 * y / spec_.height) * tan_half_fov_;
  const Vec3 direction = (forward_ + sx * right_ + sy * up_).normalized();
  return {spec_.eye, direction};
}

}  // namespace rad
