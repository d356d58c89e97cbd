// The kernel bounds behind the local pass's cluster intervals (localpass/cluster_bounds.h):
// range and Taylor remainder hold at every sampled point of random clusters, the gradient is the
// finite difference of the kernel, and the intervals they make hold on a steeply graded wall
// seen from close by (where the first moment matters most).
#include "localpass/cluster_bounds.h"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "localpass/local_pass.h"
#include "scene/scene_loader.h"

namespace rad {
namespace {

/// The kernel cos+(theta_x) cos(theta_y) / (pi r^2) straight from its definition (not the
/// h (n . u) / (pi r^4) form the code uses).
double kernel(const Vec3& x, const Vec3& n, const Vec3& y, const Vec3& normal) {
  const Vec3 u = y - x;
  const double r = u.norm();
  const double cos_x = std::max(0.0, n.dot(u) / r), cos_y = normal.dot(-u) / r;
  return cos_x * cos_y / (std::numbers::pi * r * r);
}

/// A k x k grid of faces on the square [0, size]^2 of the plane z = 0 (normal +z), with
/// exitance from `exitance(centre)`.
template <typename F>
std::vector<EmittingFace> grid(int k, double size, F exitance) {
  std::vector<EmittingFace> faces;
  const double step = size / k;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const double x0 = i * step, y0 = j * step;
      faces.push_back(
          {0,
           {{x0, y0, 0}, {x0 + step, y0, 0}, {x0 + step, y0 + step, 0}, {x0, y0 + step, 0}},
           Rgb::Constant(exitance(Vec2(x0 + step / 2, y0 + step / 2))),
           std::vector<bool>(4, false),
           Vec3::UnitZ()});
    }
  return faces;
}

TEST(KernelBounds, RangeAndTaylorRemainderHoldOnRandomClusters) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1), s(-1, 1);
  const ClusterTree tree(grid(4, 1.0, [](const Vec2&) { return 1.0; }));
  int tested = 0, expanded = 0, failures = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // x anywhere above the unit square, from very close to far, with a random upward normal.
    const Vec3 x(2 * s(rng) + 0.5, 2 * s(rng) + 0.5, std::pow(10.0, 2 * u(rng) - 1.5));
    Vec3 n(s(rng), s(rng), -u(rng));
    n.normalize();
    for (const Cluster& c : tree.clusters()) {
      const double h = x.z();
      const KernelBounds b = kernel_bounds(c, x, n, h);
      const double k_center = kernel(x, n, c.center, c.normal);
      ++tested, expanded += b.above_horizon;
      for (int sample = 0; sample < 40; ++sample) {
        // A vertex, or a random convex combination of the outline's vertices.
        Vec3 y = c.outline[sample % c.outline.size()];
        if (sample >= static_cast<int>(c.outline.size())) {
          Vec3 sum = Vec3::Zero();
          double total = 0;
          for (const Vec3& v : c.outline) {
            const double w = std::pow(u(rng), 4);
            sum += w * v, total += w;
          }
          y = sum / total;
        }
        const double k = kernel(x, n, y, c.normal);
        const double slack = 1e-12 * b.kmax;
        bool ok = k >= b.kmin - slack && k <= b.kmax + slack;
        if (b.above_horizon) {
          const double taylor = k_center + b.gradient.dot(y - c.center);
          ok = ok && std::abs(k - taylor) <= b.remainder + 1e-12 * k;
        }
        if (!ok && ++failures <= 3) {
          ADD_FAILURE() << "x " << x.transpose() << " n " << n.transpose() << " y " << y.transpose()
                        << ": k " << k << " in [" << b.kmin << ", " << b.kmax << "], taylor "
                        << k_center + b.gradient.dot(y - c.center) << " +- " << b.remainder;
        }
      }
    }
  }
  EXPECT_EQ(failures, 0);
  EXPECT_GT(expanded, tested / 4);  // the expansion took part
}

TEST(KernelBounds, GradientIsTheKernelsFiniteDifference) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> s(-1, 1);
  const ClusterTree tree(grid(2, 1.0, [](const Vec2&) { return 1.0; }));
  const Cluster& root = tree.clusters()[tree.roots().front()];
  for (int trial = 0; trial < 50; ++trial) {
    const Vec3 x(0.5 + s(rng), 0.5 + s(rng), 2 + s(rng));
    const Vec3 n = Vec3(0.2 * s(rng), 0.2 * s(rng), -1).normalized();
    const KernelBounds b = kernel_bounds(root, x, n, x.z());
    ASSERT_TRUE(b.above_horizon);
    for (const Vec3& d : {Vec3(1, 0, 0), Vec3(0, 1, 0)}) {
      const double step = 1e-5;
      const double difference = (kernel(x, n, root.center + step * d, root.normal) -
                                 kernel(x, n, root.center - step * d, root.normal)) /
                                (2 * step);
      EXPECT_NEAR(b.gradient.dot(d), difference, 1e-6 * std::abs(difference) + 1e-12)
          << "x " << x.transpose() << " n " << n.transpose();
    }
  }
}

TEST(LocalPass, BoundHoldsOnASteeplyGradedWallSeenFromCloseBy) {
  // Exitance rising from 0.1 to 2 across the wall (and a bump), points from 0.05 to 3 wall
  // widths away: cluster terms whose first moment is large. The exact values are the
  // tolerance-0 pass (equal to the plain gather, local_pass_test.cpp).
  const Scene scene = parse_scene(R"({
    "materials": {"white": {"reflectance": [0.5, 0.5, 0.5]}},
    "objects": [
      {"name": "wall", "material": "white", "polygons": [[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]]}
    ]})",
                                  "graded-wall.json");
  const std::vector<EmittingFace> faces = grid(16, 1.0, [](const Vec2& p) {
    return 0.1 + 1.9 * p.x() + 0.5 * std::exp(-20 * (p - Vec2(0.3, 0.7)).squaredNorm());
  });
  const LocalPass pass(scene, faces, Method::hemisphere);
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(0, 1), s(-1, 1);
  int violations = 0, clusters = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const Vec3 x(1.6 * u(rng) - 0.3, 1.6 * u(rng) - 0.3, std::pow(10.0, 1.8 * u(rng) - 1.3));
    const Vec3 n = Vec3(0.6 * s(rng), 0.6 * s(rng), -1).normalized();
    const Rgb exact = pass.gather(x, n, 0).irradiance;
    for (const double tolerance : {0.3, 0.1, 0.03, 0.01}) {
      const LocalPassResult r = pass.gather(x, n, tolerance);
      clusters += r.clusters;
      if ((r.irradiance - exact).cwiseAbs().maxCoeff() >
              r.bound.maxCoeff() * (1 + 1e-12) + 1e-15 * exact.maxCoeff() &&
          ++violations <= 3) {
        ADD_FAILURE() << "x " << x.transpose() << " n " << n.transpose() << " T " << tolerance
                      << ": " << r.irradiance.transpose() << " +- " << r.bound.transpose()
                      << ", exact " << exact.transpose();
      }
    }
  }
  EXPECT_EQ(violations, 0);
  EXPECT_GT(clusters, 150);  // the clusters' intervals took part
}

}  // namespace
}  // namespace rad
