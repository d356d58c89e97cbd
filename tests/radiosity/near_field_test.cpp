#include "radiosity/near_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/lambert.h"
#include "radiosity/mesher.h"

namespace rad {
namespace {

/// One unit-square patch in z = 0 facing +z, as 2 x 2 elements, one of them split again: 7
/// leaves under 4 roots.
struct Square {
  std::vector<Patch> patches;
  std::vector<Element> elements;
  Square() {
    Patch p;
    p.polygon = 0;
    p.corners = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    p.area = 1;
    patches.push_back(p);
    elements = make_elements(patches, 1);
    split_element(elements, 0);
  }
};

TEST(NearField, AverageUpGivesMeansOverAllLeavesAndSpreadsOverTheLiveOnes) {
  Square s;
  ASSERT_EQ(s.elements.size(), 8u);  // 4 roots, the 4 children of root 0
  std::vector<Rgb> value(s.elements.size(), Rgb::Zero());
  // Roots 1 to 3 are leaves; root 0's children are 4 to 7, and 7 is buried.
  ASSERT_EQ(s.elements[0].first_child, 4);
  value[1] = Rgb(2, 4, 6);
  value[2] = Rgb(3, 3, 3);
  value[3] = Rgb(0.5, 0.5, 0.5);
  value[4] = Rgb(1, 1, 1);
  value[5] = Rgb(2, 1, 1);
  value[6] = Rgb(3, 1, 1);
  value[7] = Rgb(100, 100, 100);
  std::vector<char> buried(s.elements.size(), 0);
  buried[7] = 1;
  const NearField field(1, s.elements);
  std::vector<float> spread;
  const double whole = field.average_up(s.elements, 0, value, spread, buried);
  // The mean counts every leaf by its area (a buried one is hidden from every receiver, and
  // its value is zero in a solve); the spread runs over the live leaves and the mean.
  EXPECT_NEAR(value[0][0], (1 + 2 + 3 + 100) / 4.0, 1e-12);
  EXPECT_NEAR(spread[0], 26.5 - 1, 1e-5);  // red: live 1 to 3, mean 26.5
  // The patch: live leaves 0.5 to 3, 4 and 6; means (26.5 + 2 + 3 + 0.5) / 4 = 8 in red,
  // (25.75 + 4 + 3 + 0.5) / 4 = 8.3125 in green, (25.75 + 6 + 3 + 0.5) / 4 = 8.8125 in blue.
  EXPECT_NEAR(whole, 8.8125 - 0.5, 1e-12);
}

TEST(NearField, APieceLeftWholeIsOffByNoMoreThanWhatNeedsPiecesTolerates) {
  // The bound in needs_pieces: sum_l (d_l - mean) FF_l, with FF_l the exact point-to-polygon
  // form factors of the leaves (Lambert's formula), never exceeds spread x A / (pi gap^2); so
  // a piece needs_pieces leaves whole at tolerance t costs at most t. Random densities and
  // points above the square, from touching distance to far.
  Square s;
  const NearField field(1, s.elements);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  int left_whole = 0, split = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    // A third of the trials with a buried leaf: zero, in the mean, hidden from x.
    std::vector<char> buried(s.elements.size(), 0);
    // Half the trials the worst case: one bright leaf among dark ones, seen from above it,
    // where the error nears the bound.
    const bool worst = trial % 2 == 0;
    std::vector<Rgb> value(s.elements.size(), Rgb::Zero());
    std::vector<int> leaves;
    for (size_t e = 0; e < s.elements.size(); ++e) {
      if (!s.elements[e].is_leaf()) continue;
      leaves.push_back(static_cast<int>(e));
      if (!worst) value[e] = Rgb::Constant(u(rng) * u(rng) * 10);
    }
    const int bright = leaves[static_cast<size_t>(u(rng) * leaves.size()) % leaves.size()];
    if (worst) value[bright] = Rgb::Constant(10);
    if (trial % 3 == 1) {
      // Every live leaf alike, one buried: uniform as seen, yet its mean is diluted.
      const int hidden = leaves[static_cast<size_t>(u(rng) * leaves.size()) % leaves.size()];
      for (const int l : leaves) value[l] = Rgb::Constant(5);
      buried[hidden] = 1;
      value[hidden] = Rgb::Zero();
    }
    std::vector<float> spread;
    const double whole = field.average_up(s.elements, 0, value, spread, buried);
    double mean = 0, off = 0;
    const double height = 0.01 * std::pow(2000.0, u(rng));  // to 20
    const Vec3 x =
        worst ? Vec3(s.elements[bright].centroid.x(), s.elements[bright].centroid.y(), height)
              : Vec3(-1 + 3 * u(rng), -1 + 3 * u(rng), height);
    const Vec3 n = worst ? Vec3(0, 0, -1)  // facing the square
                         : Vec3(u(rng) - 0.5, u(rng) - 0.5, -1).normalized();
    for (size_t e = 0; e < s.elements.size(); ++e) {
      if (s.elements[e].is_leaf()) mean += s.elements[e].area * value[e][0];
    }
    for (size_t e = 0; e < s.elements.size(); ++e) {
      if (s.elements[e].is_leaf() && !buried[e])
        off += (value[e][0] - mean) * point_polygon_form_factor(x, n, s.elements[e].corners);
    }
    const Sphere bounds{{0.5, 0.5, 0}, std::sqrt(0.5)};
    const double tolerated = whole * std::pow(10.0, -3 * u(rng));  // 0.001 to 1 of the spread
    if (NearField::needs_pieces(x, bounds, 1.0, whole, tolerated)) {
      ++split;
    } else {
      ++left_whole;
      EXPECT_LE(std::abs(off), tolerated) << "x " << x.transpose() << " spread " << whole;
    }
  }
  // Both outcomes occur often enough for the check to mean something.
  EXPECT_GT(left_whole, 200);
  EXPECT_GT(split, 200);
}

}  // namespace
}  // namespace rad
