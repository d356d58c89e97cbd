// Which patches a shot can reach (radiosity/receiver_culling.h): every pair it leaves out gets
// a form factor of zero from the solver's own measure, the box tree's answer is the pairwise
// rule's, a coplanar tessellation is left out whole, and a filter's back is kept.
#include "radiosity/receiver_culling.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "radiosity/mesher.h"
#include "radiosity/shooter.h"
#include "scene/ray_caster.h"
#include "tests/random_scenes.h"
#include "tests/scene_builder.h"

namespace rad {
namespace {

/// A point of the convex outline from random weights.
Vec3 point_in(const std::vector<Vec3>& corners, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  Vec3 sum = Vec3::Zero();
  double total = 0;
  for (const Vec3& c : corners) {
    const double w = u(rng);
    sum += w * c, total += w;
  }
  return sum / total;
}

TEST(ReceiverCulling, WhatItLeavesOutReceivesNothingAndTheTreeAgreesWithThePairs) {
  std::mt19937_64 rng(3);
  long culled = 0, kept = 0;
  for (uint64_t seed = 1; seed <= 12; ++seed) {
    test::RandomSceneMaker maker(seed);
    const Scene scene = maker.random_scene().scene;
    const RayCaster caster(scene);
    const Shooter rays(caster, SolverSettings{}, 1e-5 * scene.bounds().diagonal());
    const std::vector<Patch> patches = make_patches(scene, 0.3);
    const ReceiverCulling culling(patches, std::vector<char>(patches.size(), 0),
                                  scene.tolerance().in_plane, true);
    std::vector<int> receivers;
    for (int s = 0; s < static_cast<int>(patches.size()); ++s) {
      culling.receivers(s, receivers);
      std::vector<int> pairwise;
      for (int r = 0; r < static_cast<int>(patches.size()); ++r) {
        if (culling.may_receive(r, s)) pairwise.push_back(r);
      }
      ASSERT_EQ(receivers, pairwise) << "seed " << seed << ", shooter " << s;
      for (int r = 0; r < static_cast<int>(patches.size()); ++r) {
        if (culling.may_receive(r, s)) {
          ++kept;
          continue;
        }
        if (++culled % 5 != 0) continue;  // the form factors of every fifth pair left out
        for (int k = 0; k < 4; ++k) {     // its corners and points inside
          const Vec3 x = k < static_cast<int>(patches[r].corners.size())
                             ? patches[r].corners[k] + 1e-3 * (point_in(patches[r].corners, rng) -
                                                               patches[r].corners[k])
                             : point_in(patches[r].corners, rng);
          const Rgb ff =
              rays.visible_form_factor(x, patches[r].normal, patches[r].polygon, patches[s], 1);
          ASSERT_LE(ff.maxCoeff(), 1e-12)
              << "seed " << seed << ": patch " << r << " left out of patch " << s << "'s shot";
        }
      }
    }
  }
  // Both answers are common (in random scenes about four in five pairs face away).
  EXPECT_GT(culled, kept / 4) << "culled " << culled << ", kept " << kept;
  EXPECT_GT(kept, culled / 10) << "culled " << culled << ", kept " << kept;
}

TEST(ReceiverCulling, ATessellatedFloorIsLeftOutOfItsOwnShotsAndAFiltersBackIsKept) {
  test::SceneBuilder b;
  const int white = b.material("white", Rgb::Constant(0.5), Rgb::Zero());
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const Vec3 a(i, j, 0), c(i + 1, j + 1, 0);
      b.polygon({a, Vec3(i + 1, j, 0), c}, white);
      b.polygon({a, c, Vec3(i, j + 1, 0)}, white);
    }
  }
  const int above = b.rectangle(1, 2, 1, 2, 2, false, white);  // its front up: its back down
  const Scene& scene = b.scene();
  const std::vector<Patch> patches = make_patches(scene, 0.5);
  std::vector<char> back(patches.size(), 0);
  for (size_t p = 0; p < patches.size(); ++p) back[p] = patches[p].polygon == above;
  const ReceiverCulling one_sided(patches, std::vector<char>(patches.size(), 0),
                                  scene.tolerance().in_plane, true);
  const ReceiverCulling filter(patches, back, scene.tolerance().in_plane, true);
  std::vector<int> receivers;
  for (int s = 0; s < static_cast<int>(patches.size()); ++s) {
    if (patches[s].polygon == above) continue;
    one_sided.receivers(s, receivers);
    EXPECT_TRUE(receivers.empty()) << "floor patch " << s << " reaches " << receivers.size();
    filter.receivers(s, receivers);
    ASSERT_FALSE(receivers.empty());
    for (const int r : receivers) EXPECT_EQ(patches[r].polygon, above);
  }
  // A scene with mirrors culls nothing: a receiver behind a shooter may see its image.
  const ReceiverCulling off(patches, back, scene.tolerance().in_plane, false);
  off.receivers(0, receivers);
  EXPECT_EQ(receivers.size(), patches.size());
}

}  // namespace
}  // namespace rad
