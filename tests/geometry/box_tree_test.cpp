// The box hierarchy finds what a pass over every box finds: every query, any_of and pairs
// against brute force, on seeded random boxes (points, slivers, nested, far apart), in 2D and 3D.
#include "geometry/box_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "geometry/vec.h"

namespace rad {
namespace {

template <int Dim>
using Box = typename BoxTree<Dim>::Box;

template <int Dim>
Box<Dim> random_box(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> where(-10, 10), size(0, 3);
  using Point = Eigen::Matrix<double, Dim, 1>;
  Point low, high;
  for (int a = 0; a < Dim; ++a) {
    low[a] = where(rng);
    // A tenth are points or slivers, flat along one axis.
    const double extent = rng() % 10 == 0 ? 0.0 : size(rng);
    high[a] = low[a] + extent;
  }
  return Box<Dim>(low, high);
}

template <int Dim>
void check_against_brute_force(uint64_t seed) {
  std::mt19937_64 rng(seed);
  const int n = static_cast<int>(rng() % 300);  // none, one, a few, many
  std::vector<Box<Dim>> boxes;
  for (int i = 0; i < n; ++i) boxes.push_back(random_box<Dim>(rng));
  if (n > 2) boxes[1] = boxes[0];  // a duplicate
  const BoxTree<Dim> tree(boxes);
  for (int trial = 0; trial < 50; ++trial) {
    const Box<Dim> query = random_box<Dim>(rng);
    std::vector<int> expected, found;
    for (int i = 0; i < n; ++i) {
      if (boxes[i].intersects(query)) expected.push_back(i);
    }
    tree.query(query, [&](int i) { found.push_back(i); });
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, expected) << "seed " << seed << " trial " << trial;
    EXPECT_EQ(tree.any(query), !expected.empty());
    // any_of asks until its predicate holds: here, for odd items only.
    const bool odd = std::any_of(expected.begin(), expected.end(), [](int i) { return i % 2; });
    EXPECT_EQ(tree.any_of(query, [](int i) { return i % 2 == 1; }), odd);
  }
  for (int i = 0; i < n; ++i) EXPECT_EQ(tree.box(i).min(), boxes[i].min());
  // pairs against a second tree.
  std::vector<Box<Dim>> others;
  for (int i = 0; i < 40; ++i) others.push_back(random_box<Dim>(rng));
  const BoxTree<Dim> other(others);
  std::vector<std::pair<int, int>> expected, found;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < 40; ++j) {
      if (boxes[i].intersects(others[j])) expected.emplace_back(i, j);
    }
  }
  tree.pairs(other, [&](int i, int j) { found.emplace_back(i, j); });
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, expected) << "seed " << seed;
}

TEST(BoxTree, FindsWhatAPassOverEveryBoxFinds3D) {
  for (uint64_t seed = 1; seed <= 20; ++seed) check_against_brute_force<3>(seed);
}

TEST(BoxTree, FindsWhatAPassOverEveryBoxFinds2D) {
  for (uint64_t seed = 1; seed <= 20; ++seed) check_against_brute_force<2>(seed);
}

TEST(BoxTree, NearestFirstVisitsWhatItEntersOnceAndTheNearestFirst) {
  // The visibility culling's walk (localpass/visible_set.h): with every node entered, each item
  // once, the nearest box first; with nodes entered only where they meet a query box, every
  // item meeting it still (its leaf and the nodes above hold its box), and none twice.
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    std::mt19937_64 rng(seed);
    std::vector<Box<3>> boxes;
    const int n = static_cast<int>(rng() % 300);
    for (int i = 0; i < n; ++i) boxes.push_back(random_box<3>(rng));
    const BoxTree<3> tree(boxes);
    const Box<3> probe = random_box<3>(rng);
    const Eigen::Vector3d point = probe.center();
    std::vector<int> all;
    tree.nearest_first(
        point, [](const Box<3>&) { return true; }, [&](int item) { all.push_back(item); });
    std::vector<int> sorted = all;
    std::ranges::sort(sorted);
    ASSERT_EQ(sorted.size(), boxes.size());
    for (int i = 0; i < n; ++i) ASSERT_EQ(sorted[i], i);
    if (n > 0) {
      double nearest = boxes[0].squaredExteriorDistance(point);
      for (const Box<3>& b : boxes) nearest = std::min(nearest, b.squaredExteriorDistance(point));
      EXPECT_EQ(boxes[all.front()].squaredExteriorDistance(point), nearest);
    }
    std::vector<int> met;
    tree.nearest_first(
        point, [&](const Box<3>& b) { return b.intersects(probe); },
        [&](int item) { met.push_back(item); });
    std::ranges::sort(met);
    EXPECT_TRUE(std::ranges::adjacent_find(met) == met.end());
    for (int i = 0; i < n; ++i) {
      if (boxes[i].intersects(probe)) {
        EXPECT_TRUE(std::ranges::binary_search(met, i)) << i;
      }
    }
  }
}

TEST(BoxTree, EmptyTreeFindsNothing) {
  const BoxTree<3> tree;
  EXPECT_FALSE(tree.any(BoxTree<3>::Box(Vec3::Zero(), Vec3::Ones())));
}

}  // namespace
}  // namespace rad
