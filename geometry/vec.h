#pragma once
/// The vector types that run through every module: double precision everywhere in geometry and
/// energy code (STYLE.md rule 4); float appears only at the Embree and image-file boundaries.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace rad {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
/// Linear RGB triple: reflectance (unitless), exitance or irradiance (W/m^2), radiance.
using Rgb = Eigen::Vector3d;

/// The angle between two non-zero vectors, atan2(|a x b|, a . b): accurate near 0 and pi alike
/// (DESIGN.md §7), where acos of the normalised dot product loses half the digits.
inline double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// Distance from point p to the segment [a, b] (2D or 3D; a point for a = b).
template <class V>
double point_segment_distance(const V& p, const V& a, const V& b) {
  const V ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

/// The axis-aligned box of a set of points (empty for none).
inline Eigen::AlignedBox3d bounding_box(const std::vector<Vec3>& points) {
  Eigen::AlignedBox3d box;
  for (const Vec3& p : points) box.extend(p);
  return box;
}

}  // namespace rad
