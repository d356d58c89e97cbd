#pragma once
/// Pinhole camera of the scene file's "camera" block (DESIGN.md §5).
#include "geometry/vec.h"
#include "scene/ray.h"

namespace rad {

/// The camera as written in the scene file.
struct CameraSpec {
  Vec3 eye{0, 0, 0};
  Vec3 look_at{0, 0, 1};
  Vec3 up{0, 1, 0};
  double fov_deg = 45;  ///< Full vertical field of view, degrees, in (0, 180).
  int width = 512;      ///< Image width in pixels.
  int height = 512;     ///< Image height in pixels.
};

/// A pinhole camera. Pixel (0, 0) is the top-left corner of the image; the pixel with integer
/// index (i, j) spans [i, i+1) x [j, j+1) in raster coordinates. The vertical field of view is
/// `fov_deg`; the horizontal one follows from the aspect ratio width/height.
class Camera {
 public:
  /// Throws InputError when the spec is degenerate (eye == look_at, up parallel to the view
  /// direction, fov outside (0, 180), non-positive size).
  explicit Camera(const CameraSpec& spec);

  /// The primary ray through raster position (x, y); the pixel centre of (i, j) is
  /// (i + 0.5, j + 0.5). Direction is unit length; origin is the eye.
  Ray ray(double x, double y) const;

  const CameraSpec& spec() const { return spec_; }
  int width() const { return spec_.width; }
  int height() const { return spec_.height; }
  /// Unit camera frame: `forward` looks at look_at, `right` and `up` span the image plane.
  const Vec3& forward() const { return forward_; }
  const Vec3& right() const { return right_; }
  const Vec3& up() const { return up_; }

 private:
  CameraSpec spec_;
  Vec3 forward_, right_, up_;
  double tan_half_fov_ = 0;
};

}  // namespace rad
