#pragma once
/// The vector types that run through every module: double precision everywhere in geometry and
/// energy code (STYLE.md rule 4); float appears only at the Embree and image-file boundaries.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace rad {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
/// Linear RGB triple: reflectance (unitless), exitance or irradiance (W/m^2), radiance.
using Rgb = Eigen::Vector3d;

/// The axis-aligned box of a set of points (empty for none).
inline Eigen::AlignedBox3d bounding_box(const std::vector<Vec3>& points) {
  Eigen::AlignedBox3d box;
  for (const Vec3& p : points) box.extend(p);
  return box;
}

}  // namespace rad
