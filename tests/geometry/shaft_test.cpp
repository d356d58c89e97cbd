// The shaft from a point to a box (shaft culling, Haines and Wallace 1994) holds every segment
// from the point to the box, and leaves most far points out.
#include "geometry/shaft.h"

#include <gtest/gtest.h>

#include <iostream>
#include <random>

namespace rad {
namespace {

TEST(Shaft, HoldsEverySegmentFromThePointToTheBox) {
  // Seeded boxes (some flat, as an element's box is), points outside, inside and on their
  // faces: every point of every segment to the box may meet the shaft; far points mostly not.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int rejected = 0, far_points = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    if (trial % 3 == 0) b[trial % 2] = a[trial % 2];  // flat
    const Eigen::AlignedBox3d box(a.cwiseMin(b), a.cwiseMax(b));
    Vec3 x = 3 * Vec3(u(rng), u(rng), u(rng));
    if (trial % 5 == 0) x = box.center();                            // inside
    if (trial % 7 == 0) x[0] = box.min().x(), x[1] = box.max().y();  // in a face's plane
    const Shaft shaft(x, box, 1e-9);
    for (int k = 0; k < 20; ++k) {
      const Vec3 y =
          box.min() +
          (box.max() - box.min()).cwiseProduct(0.5 * (Vec3(u(rng), u(rng), u(rng)) + Vec3::Ones()));
      const Vec3 p = x + 0.5 * (1 + u(rng)) * (y - x);
      ASSERT_TRUE(shaft.may_meet({p})) << "trial " << trial;
      const Vec3 far = 3 * Vec3(u(rng), u(rng), u(rng));
      ++far_points;
      rejected += !shaft.may_meet({far});
    }
  }
  EXPECT_GT(rejected, far_points / 2);  // measured: 39,902 of 40,000
  std::cout << rejected << " of " << far_points << " random points outside the shafts\n";
}

}  // namespace
}  // namespace rad
