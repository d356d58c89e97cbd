#pragma once
/// Checks on RGB results shared by the suites: per-channel agreement with the inputs printed,
/// a seeded estimator's mean with its standard error, and seeded points on gatherer faces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "geometry/emitting_face.h"
#include "scene/scene.h"

namespace rad::test {

/// Per channel within `relative` of `want`, or 1e-12 absolute.
inline ::testing::AssertionResult agree(const Rgb& got, const Rgb& want, double relative = 1e-9) {
  for (int c = 0; c < 3; ++c) {
    const double tolerance = std::max(relative * std::abs(want[c]), 1e-12);
    if (!(std::abs(got[c] - want[c]) <= tolerance)) {
      return ::testing::AssertionFailure() << "channel " << c << ": got " << got[c] << " want "
                                           << want[c] << " (difference " << got[c] - want[c] << ")";
    }
  }
  return ::testing::AssertionSuccess();
}

/// Mean of `seeds` runs of a seeded estimator and the standard error of that mean, per channel.
struct SampledMean {
  Rgb mean = Rgb::Zero(), standard_error = Rgb::Zero();
};
inline SampledMean sampled_mean(int seeds, const std::function<Rgb(int seed)>& estimate) {
  Rgb sum = Rgb::Zero(), sum2 = Rgb::Zero();
  for (int k = 0; k < seeds; ++k) {
    const Rgb m = estimate(k);
    sum += m;
    sum2 += m.cwiseProduct(m);
  }
  SampledMean out;
  out.mean = sum / seeds;
  const Rgb variance =
      ((sum2 / seeds - out.mean.cwiseProduct(out.mean)) * seeds / (seeds - 1.0)).cwiseMax(0);
  out.standard_error = (variance / seeds).cwiseSqrt();
  return out;
}

struct FacePoint {
  Vec3 x, n;
};
/// Seeded points on the faces (area-blind: every face alike), with their polygons' normals, as
/// primary hits would be.
inline std::vector<FacePoint> face_points(const Scene& scene,
                                          const std::vector<EmittingFace>& faces, int count,
                                          uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<FacePoint> points;
  for (int i = 0; i < count; ++i) {
    const EmittingFace& f = faces[static_cast<size_t>(u(rng) * faces.size()) % faces.size()];
    double a = u(rng), b = u(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    points.push_back(
        {f.vertices[0] + a * (f.vertices[1] - f.vertices[0]) + b * (f.vertices[2] - f.vertices[0]),
         scene.polygons[f.polygon].normal});
  }
  return points;
}

}  // namespace rad::test
