// The energy-bounded octree: structure, the box silhouette form factor against Monte Carlo, and
// the property that every voxel bound covers what the voxel's patches can send.
#include "octree/octree.h"

#include <gtest/gtest.h>

#include <random>

#include "geometry/lambert.h"
#include "hemisphere/hemisphere_gatherer.h"
#include "localpass/local_pass.h"
#include "scene/polygon_faces.h"
#include "tests/coarse_solution.h"

namespace rad {
namespace {

const test::SolvedScene& cornell() { return test::coarse_cornell(); }

TEST(Octree, EveryItemInExactlyOneLeafInsideItsBounds) {
  const test::SolvedScene& c = cornell();
  const Octree tree(octree_items(c.faces));
  std::vector<int> seen(c.faces.size(), 0);
  for (const int v : tree.leaves()) {
    const Voxel& leaf = tree.voxels()[v];
    EXPECT_TRUE(leaf.is_leaf());
    Rgb bmax = Rgb::Zero();
    for (const int i : leaf.items) {
      ++seen[i];
      for (const Vec3& corner : tree.items()[i].corners) EXPECT_TRUE(leaf.bounds.contains(corner));
      bmax = bmax.cwiseMax(tree.items()[i].radiosity);
    }
    EXPECT_EQ(leaf.bmax, bmax);
  }
  for (size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], 1) << "item " << i;
  // The criterion splits: more than one leaf, and the root's bmax is the largest radiosity.
  EXPECT_GT(tree.leaves().size(), 8u);
  EXPECT_EQ(tree.items_below(0).size(), c.faces.size());
}

/// Fraction of cosine-weighted directions from x that hit the box (slab test), seeded.
double box_form_factor_monte_carlo(const Eigen::AlignedBox3d& box, const Vec3& x, const Vec3& n,
                                   int samples, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const PlaneFrame frame(Vec3::Zero(), n);
  int hits = 0;
  for (int s = 0; s < samples; ++s) {
    const double r1 = u(rng), r2 = u(rng), r = std::sqrt(r1), phi = 2 * std::numbers::pi * r2;
    const Vec3 d =
        r * std::cos(phi) * frame.u + r * std::sin(phi) * frame.v + std::sqrt(1 - r1) * n;
    double t0 = 0, t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      if (d[a] == 0) {
        if (x[a] < box.min()[a] || x[a] > box.max()[a]) t0 = t1 + 1;
        continue;
      }
      double ta = (box.min()[a] - x[a]) / d[a], tb = (box.max()[a] - x[a]) / d[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    if (t0 <= t1) ++hits;
  }
  return static_cast<double>(hits) / samples;
}

TEST(Octree, MaxVoxelsBoundsEveryTreeEvenWhenItemsCrowdOnePoint) {
  // Seeded soups of small triangles: spread over a box, and crowded near one corner so that
  // splitting runs to max_level; one bright item keeps the energy criterion from stopping it.
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(0, 1);
  for (const int n : {1, 5, 6, 40, 500, 3000}) {
    for (const double spread : {1.0, 1e-6}) {
      std::vector<OctreeItem> items(static_cast<size_t>(n));
      for (size_t i = 0; i < items.size(); ++i) {
        const Vec3 p = spread * Vec3(u(rng), u(rng), u(rng));
        items[i].corners = {p, p + Vec3(spread * 1e-3, 0, 0), p + Vec3(0, spread * 1e-3, 0)};
        items[i].radiosity = Rgb::Constant(i == 0 ? 1e6 : u(rng));
      }
      items.push_back({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, Vec3::UnitZ(), Rgb::Ones()});
      const long long count = static_cast<long long>(items.size());
      const Octree tree(std::move(items));
      EXPECT_LE(static_cast<long long>(tree.voxels().size()), Octree::max_voxels(count))
          << n << " items, spread " << spread;
    }
  }
  // By hand: one item is a leaf root; five items in one octant at every level split down to
  // max_level (8): one inner voxel a level, 8 children each.
  EXPECT_EQ(Octree::max_voxels(1), 1);
  EXPECT_EQ(Octree::max_voxels(5), 1 + 8 * 8);
}

TEST(Octree, BoxFormFactorMatchesMonteCarloAndIsOneInside) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  const int samples = 200000;
  for (int trial = 0; trial < 40; ++trial) {
    const Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    const Eigen::AlignedBox3d box(a.cwiseMin(b), a.cwiseMax(b));
    const Vec3 x = 2.5 * Vec3(u(rng), u(rng), u(rng));
    const Vec3 n = Vec3(u(rng), u(rng), u(rng)).normalized();
    const double exact = box_form_factor(box, x, n);
    const double mc = box_form_factor_monte_carlo(box, x, n, samples, rng);
    // Binomial standard deviation; 5 sigma plus a floor.
    const double sigma = std::sqrt(std::max(mc * (1 - mc), 1e-6) / samples);
    EXPECT_NEAR(exact, mc, 5 * sigma + 1e-4) << "trial " << trial;
  }
  const Eigen::AlignedBox3d unit(Vec3::Zero(), Vec3::Ones());
  EXPECT_EQ(box_form_factor(unit, Vec3(0.5, 0.5, 0.5), Vec3::UnitZ()), 1.0);
  EXPECT_EQ(box_form_factor(unit, Vec3(0, 0.5, 0.5), Vec3::UnitX()), 1.0);  // on a face
  // Seen from straight above one face only: that face's form factor.
  const std::vector<Vec3> top{{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  EXPECT_DOUBLE_EQ(box_form_factor(unit, Vec3(0.5, 0.5, 3), -Vec3::UnitZ()),
                   point_polygon_form_factor(Vec3(0.5, 0.5, 3), -Vec3::UnitZ(), top));
}

TEST(Octree, BoundsCoverWhatEachVoxelCanSendOverRandomTriples) {
  // Property (004 eqs. 7-8): for random (x, n, voxel), the bound is at least the exact
  // contribution of the voxel's items, each radiating its radiosity, occluded by one another
  // (nothing else can add light). Exact by the hemisphere gatherer over the voxel's faces.
  const test::SolvedScene& c = cornell();
  const Octree tree(octree_items(c.faces));
  const auto& voxels = tree.voxels();
  std::vector<int> nonempty;
  std::vector<std::unique_ptr<HemisphereGatherer>> gatherers(voxels.size());
  for (size_t v = 0; v < voxels.size(); ++v) {
    if (voxels[v].item_count == 0) continue;
    nonempty.push_back(static_cast<int>(v));
    std::vector<EmittingFace> faces;
    for (const int i : tree.items_below(static_cast<int>(v))) faces.push_back(c.faces[i]);
    gatherers[v] = std::make_unique<HemisphereGatherer>(std::move(faces), c.scene.tolerance());
  }
  const auto box = c.scene.bounds();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1), s(-1, 1);
  int violations = 0, violations7 = 0, lit = 0;
  const int triples = 100000;
  for (int t = 0; t < triples; ++t) {
    // Half the points on random faces (as the local pass sees them), half anywhere in the box.
    Vec3 x, n;
    if (t % 2 == 0) {
      const EmittingFace& f =
          c.faces[static_cast<size_t>(u(rng) * c.faces.size()) % c.faces.size()];
      double a = u(rng), b = u(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      x = f.vertices[0] + a * (f.vertices[1] - f.vertices[0]) + b * (f.vertices[2] - f.vertices[0]);
      n = c.scene.polygons[f.polygon].normal;
    } else {
      x = box.lo + (box.hi - box.lo).cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
      n = Vec3(s(rng), s(rng), s(rng)).normalized();
    }
    const int v = nonempty[static_cast<size_t>(u(rng) * nonempty.size()) % nonempty.size()];
    const Rgb exact = gatherers[v]->gather(x, n).irradiance;
    const Rgb bound = tree.bound(v, x, n), bound7 = tree.bound_eq7(v, x, n);
    if (exact.maxCoeff() > 0) ++lit;
    const Rgb slack = Rgb::Constant(1e-12) + 1e-12 * exact;
    if (((exact - bound).array() > slack.array()).any() && ++violations <= 5) {
      ADD_FAILURE() << "eq. 8 bound " << bound.transpose() << " < exact " << exact.transpose()
                    << " at voxel " << v;
    }
    if (((exact - bound7).array() > slack.array()).any()) ++violations7;
    if (((bound - bound7).array() > 1e-15).any())
      ADD_FAILURE() << "eq. 8 looser than eq. 7 at voxel " << v;
  }
  EXPECT_EQ(violations, 0);
  EXPECT_EQ(violations7, 0);
  EXPECT_GT(lit, triples / 10);  // the test meets many voxels that do send light
}

}  // namespace
}  // namespace rad
