// The hierarchical solver (radiosity/hierarchical_solver.h): the furnace's closed form, the
// progressive solver as its peer on the Cornell box, a far cluster and a point light against
// closed forms, a closed room's ledger, a slab that hides a room whole, the same bytes for any
// thread count, and the scenes it does not carry yet. (Its bound against the same links swept
// further: tests/radiosity/error_bound_test.cpp, with the progressive solver's.)
#include "radiosity/hierarchical_solver.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <numbers>

#include "radiosity/solver.h"
#include "scene/error.h"
#include "scene/scene_loader.h"
#include "tests/scene_builder.h"

namespace rad {
namespace {

const std::filesystem::path kScenes = std::filesystem::path(RAD_SOURCE_DIR) / "data";

Solution solve_with(const Scene& scene, SolverSettings settings, SolverSettings::Method method) {
  settings.method = method;
  const RayCaster caster(scene);
  return solve(caster, settings);
}

constexpr auto kHierarchical = SolverSettings::Method::hierarchical;
constexpr auto kProgressive = SolverSettings::Method::progressive;

/// The closed unit room at the origin, rho 0.5, a point light at (0.5, 0.5, 0.6), and either a
/// second closed room [lo, hi] of the same wall or, in its place, a small black marker at its
/// corner hi, so that both scenes have the same bounds (the patch size is a fraction of their
/// diagonal) and so the first room the same mesh.
Scene lit_room_and(const Vec3& lo, const Vec3& hi, bool second_room) {
  test::SceneBuilder b;
  const int wall = b.material("wall", Rgb::Constant(0.5), Rgb::Zero());
  b.room(Vec3(0, 0, 0), Vec3(1, 1, 1), wall);
  if (second_room) {
    b.room(lo, hi, wall);
  } else {
    const int black = b.material("black", Rgb::Zero(), Rgb::Zero());
    const Vec3 step(0, 0.01, 0.01);
    b.polygon({hi, hi - Vec3(0, step.y(), 0), hi - step}, black);
  }
  b.scene().lights.push_back({Vec3(0.5, 0.5, 0.6), Rgb::Ones()});
  return b.scene();
}

TEST(HierarchicalSolver, FurnaceIsEOverOneMinusRho) {
  // The closed cube, E = 1 everywhere, rho = (0.2, 0.5, 0.8): B = E / (1 - rho) = (1.25, 2, 5)
  // exactly where every receiver's form factors sum to 1. At this size every pair is near, so
  // the links are the exact point-to-element form factors, whose rows sum to 1 in a closed
  // room (measured: 1 at every element, so none was scaled down): the largest error measured
  // is 3e-9 in red, 9e-9 in green (the links' factors are floats) and 6.5e-7 in blue (rho 0.8;
  // the sweeps stop at 1e-6 of the light).
  Scene cube = load_scene(kScenes / "closed-cube/scene.json");
  cube.materials[0].reflectance = Rgb(0.2, 0.5, 0.8);
  const Rgb exact(1.25, 2, 5);
  SolverSettings settings;
  settings.patch_size = 0.25;
  settings.unshot_fraction = 1e-6;
  const Solution s = solve_with(cube, settings, kHierarchical);
  ASSERT_GT(s.stats.links, 0);
  Rgb worst = Rgb::Zero(), mean = Rgb::Zero();
  double area = 0;
  for (const int e : s.leaves()) {
    const Element& el = s.elements[e];
    const Rgb relative = (el.radiosity - exact).cwiseQuotient(exact);
    worst = worst.cwiseMax(relative.cwiseAbs());
    mean += relative * el.area;
    area += el.area;
  }
  mean /= area;
  std::cout << "furnace: largest relative error (" << worst.transpose() << "), mean ("
            << mean.transpose() << ")\n";
  EXPECT_LT(worst.maxCoeff(), 1e-4);
  EXPECT_LT(mean.cwiseAbs().maxCoeff(), 1e-4);
}

TEST(HierarchicalSolver, AgreesWithTheProgressiveSolverOnTheCornellBox) {
  // The progressive solver is the independent peer: the same mesh (no refinement), its own
  // shots and form factors. Measured: the power absorbed agrees to 0.4% per channel and the
  // patches' radiosity to an area-weighted RMS of 2.7% (the clusters' and centroids'
  // approximations); a solver that missed a bounce, or a cluster's flux in the wrong bins, is
  // off by far more.
  const Scene scene = load_scene(kScenes / "cornell-box/scene.json");
  SolverSettings settings;
  settings.patch_size = 0.12;
  settings.refine_threshold = 0;
  const Solution h = solve_with(scene, settings, kHierarchical);
  const Solution p = solve_with(scene, settings, kProgressive);
  ASSERT_EQ(h.patches.size(), p.patches.size());
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(h.stats.absorbed[c], p.stats.absorbed[c], 1e-2 * p.stats.absorbed[c])
        << "channel " << c;
  }
  double squares = 0, area = 0;
  for (size_t i = 0; i < p.patches.size(); ++i) {
    const double reference = p.patches[i].radiosity.sum();
    if (!(reference > 0)) continue;
    const double relative = h.patches[i].radiosity.sum() / reference - 1;
    squares += relative * relative * p.patches[i].area;
    area += p.patches[i].area;
  }
  const double rms = std::sqrt(squares / area);
  std::cout << "Cornell box, hierarchical against progressive: absorbed ("
            << h.stats.absorbed.cwiseQuotient(p.stats.absorbed).transpose() << "), patches' RMS "
            << rms << "\n";
  EXPECT_LT(rms, 0.03);
}

TEST(HierarchicalSolver, AFarClusterSendsTheFluxOfTheFacesTurnedToTheReceiver) {
  // A 1 x 1 receiver (rho 0.5) 10 away from a lamp of the same size facing it (E = 1), with a
  // brighter one (E = 3) back to back with the lamp, facing away. The lamp pair is one cluster
  // far away (size 1.4 < kOpening x 10): only the facing lamp's flux may reach the receiver.
  // Closed form (Howell's catalog, a point to a parallel rectangle, by its four quarters):
  // F = (2 / pi) (X / sqrt(1 + X^2) atan(X / sqrt(1 + X^2))) x 2, X = 1 / (2 x 10), at the
  // centre; 0.5% lower at the corners (measured: the mean 0.1% below the centre). A cluster
  // that sent its flux the wrong way gives 3x; rays to the wrong patches, a third less.
  test::SceneBuilder b;
  const int receiver = b.material("receiver", Rgb::Constant(0.5), Rgb::Zero());
  const int lamp = b.material("lamp", Rgb::Zero(), Rgb::Ones());
  const int bright = b.material("bright", Rgb::Zero(), Rgb::Constant(3));
  b.rectangle(-0.5, 0.5, -0.5, 0.5, 0, false, receiver);
  b.rectangle(-0.5, 0.5, -0.5, 0.5, 10, true, lamp);
  b.rectangle(-0.5, 0.5, -0.5, 0.5, 10.01, false, bright);
  SolverSettings settings;
  settings.patch_size = 0.02;
  const Solution s = solve_with(b.scene(), settings, kHierarchical);
  const double x = 1.0 / 20, root = std::sqrt(1 + x * x);
  const double ff = 4 / (2 * std::numbers::pi) * 2 * (x / root) * std::atan(x / root);
  double sum = 0, area = 0;
  for (const int e : s.leaves()) {
    const Element& el = s.elements[e];
    if (el.polygon != 0) continue;
    sum += el.radiosity[0] * el.area;
    area += el.area;
  }
  const double mean = sum / area;
  std::cout << "far cluster: receiver's mean radiosity " << mean << ", closed form at the centre "
            << 0.5 * ff << "\n";
  EXPECT_NEAR(mean, 0.5 * ff, 0.01 * 0.5 * ff);
}

TEST(HierarchicalSolver, APointLightReachesEachLeafByTheInverseSquareCosineLaw) {
  // A 2 x 2 floor (rho 0.5) under a point light of intensity I = (1, 2, 3) W/sr at height 0.3
  // over its centre, nothing else: each leaf's irradiance is I cos / r^2 at its centroid
  // (computed here), its radiosity rho times that (a flat floor sees nothing of itself), and
  // the floor takes I times its solid angle, 4 asin(a b / sqrt((a^2 + 4h^2)(b^2 + 4h^2)))
  // (Howell's catalog), to the midpoint rule's error (measured: 0.05%). Refinement splits the
  // floor under the light (its fall-off is off the neighbours' plane: 292 leaves), so new
  // leaves are lit too.
  test::SceneBuilder b;
  b.rectangle(-1, 1, -1, 1, 0, false, b.material("floor", Rgb::Constant(0.5), Rgb::Zero()));
  const Vec3 lamp(0, 0, 0.3);
  const Rgb intensity(1, 2, 3);
  b.scene().lights.push_back({lamp, intensity});
  SolverSettings settings;
  settings.patch_size = 0.05;
  settings.refine_threshold = 0.01;
  const Solution s = solve_with(b.scene(), settings, kHierarchical);
  EXPECT_GT(s.stats.refined, 0);
  Rgb power = Rgb::Zero();
  double worst = 0;
  for (const int e : s.leaves()) {
    const Element& el = s.elements[e];
    const Vec3 to = lamp - el.centroid;
    const Rgb exact = intensity * (to.z() / std::pow(to.norm(), 3));
    worst = std::max(worst, ((el.irradiance - exact).cwiseQuotient(exact)).cwiseAbs().maxCoeff());
    worst = std::max(
        worst, ((el.radiosity - 0.5 * exact).cwiseQuotient(0.5 * exact)).cwiseAbs().maxCoeff());
    power += el.irradiance * el.area;
  }
  EXPECT_LT(worst, 1e-9);
  const double solid_angle = 4 * std::asin(4.0 / (4.0 + 4 * 0.3 * 0.3));
  std::cout << "floor under a point light: " << s.stats.refined << " split, power ("
            << power.transpose() << "), closed form " << solid_angle << " I\n";
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(power[c], intensity[c] * solid_angle, 2e-3 * intensity[c] * solid_angle);
  // The ledger: the light's power is emitted; what misses the floor escapes.
  const Rgb light_power = 4 * std::numbers::pi * intensity;
  EXPECT_LT((s.stats.emitted - light_power).cwiseAbs().maxCoeff(), 1e-9 * light_power.maxCoeff());
  EXPECT_LT((s.stats.absorbed - 0.5 * power).cwiseAbs().maxCoeff(), 1e-9 * power.maxCoeff());
}

TEST(HierarchicalSolver, AClosedRoomAbsorbsAllOfAPointLightsPower) {
  // The closed cube, dark (E = 0), rho = (0.2, 0.5, 0.8), a point light at its centre: nothing
  // escapes, so what the walls absorb, sum (1 - rho) H A, is what the light delivers to the
  // leaves, D = sum I cos / r^2 A at their centroids (computed here; 4 pi I to the midpoint
  // rule), however many bounces it takes (measured: within 0.1% of D in every channel, D
  // 0.8% above 4 pi I at this mesh). A light left out of the gather, or counted on a leaf's
  // radiosity without its reflection, breaks it by its whole share. So does a leaf taking a
  // near source whole, at its mean (kSourceRadii): at 3 radii blue absorbs 1.6% too little,
  // at 5 radii 0.36%.
  Scene cube = load_scene(kScenes / "closed-cube/scene.json");
  cube.materials[0].reflectance = Rgb(0.2, 0.5, 0.8);
  cube.materials[0].emission = Rgb::Zero();
  const Vec3 lamp(0.5, 0.5, 0.5);
  cube.lights.push_back({lamp, Rgb::Ones()});
  SolverSettings settings;
  settings.patch_size = 0.2;
  settings.unshot_fraction = 1e-6;
  const Solution s = solve_with(cube, settings, kHierarchical);
  double delivered = 0;
  for (const int e : s.leaves()) {
    const Element& el = s.elements[e];
    const Vec3 to = lamp - el.centroid;
    delivered += s.patches[el.patch].normal.dot(to) / std::pow(to.norm(), 3) * el.area;
  }
  std::cout << "closed room lit by a point light: absorbed (" << s.stats.absorbed.transpose()
            << "), delivered " << delivered << ", 4 pi " << 4 * std::numbers::pi << "\n";
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.stats.absorbed[c], delivered, 2e-3 * delivered);
  EXPECT_NEAR(delivered, 4 * std::numbers::pi, 0.02 * 4 * std::numbers::pi);
}

TEST(HierarchicalSolver, ADarkClosedRoomTakesNoLinksAndChangesNothingBesideIt) {
  // Two closed unit rooms side by side, rho 0.5, a point light in the first; the second is
  // dark, whatever the solver does (nothing reaches it). What a source may bring a receiver
  // is its form factor times its radiosity, 0 for every source of the dark room, so linking
  // leaves its clusters out (Hanrahan, Salzman and Aupperle's BF refinement): its leaves take
  // no links and the lit room's leaves the same light as without it. The lit room alone is
  // solved with a black marker where the dark room's far corner is, so that both scenes have
  // the same bounds (the patch size is a fraction of their diagonal) and so the same mesh.
  // Measured: the same links, radiosity the same to 1e-15. Linking the dark room as the lit
  // one doubles the links.
  const auto scene = [](bool dark_room) {
    return lit_room_and(Vec3(2, 0, 0), Vec3(3, 1, 1), dark_room);
  };
  SolverSettings settings;
  settings.refine_threshold = 0;
  const Solution alone = solve_with(scene(false), settings, kHierarchical);
  const Solution both = solve_with(scene(true), settings, kHierarchical);
  std::cout << "a dark room beside a lit one: " << both.stats.links << " links, "
            << alone.stats.links << " without it; " << both.stats.left_out
            << " sources left out, bringing at most " << both.stats.left_out_bound << "\n";
  EXPECT_LE(both.stats.links, alone.stats.links);
  settings.faint_share = 0;
  const Solution by_geometry = solve_with(scene(true), settings, kHierarchical);
  std::cout << "linked by geometry alone: " << by_geometry.stats.links << " links\n";
  EXPECT_GT(by_geometry.stats.links, both.stats.links);
  double lit = 0, dark = 0, difference = 0;
  for (const int e : both.leaves()) {
    const Element& el = both.elements[e];
    if (el.centroid.x() > 1.5) {
      dark = std::max(dark, el.radiosity.maxCoeff());
      continue;
    }
    // (The lit room's polygons come first in both scenes, with the same elements.)
    ASSERT_EQ(el.centroid, alone.elements[e].centroid);
    lit = std::max(lit, el.radiosity.maxCoeff());
    difference =
        std::max(difference, (el.radiosity - alone.elements[e].radiosity).cwiseAbs().maxCoeff());
  }
  EXPECT_GT(lit, 0.01);
  EXPECT_EQ(dark, 0.0);
  EXPECT_LT(difference, 1e-9 * lit);
}

TEST(HierarchicalSolver, ASlabHidesTheRoomAboveWholeAndTheLightStaysWhereItWas) {
  // Two closed unit rooms, one above the other with a slab's gap between them, rho 0.5, a
  // point light in each: no light passes between them. Linking drops what one polygon hides
  // from every point that gathers (HierarchicalSolver::hidden_whole): the lower room's ceiling
  // hides the upper room from the lower room's leaves but those on its walls (their centroids
  // lie in the walls' planes, and so do the segments to the upper room's walls' corners, along
  // the ceiling's edges), and the upper room's floor the lower room from the upper room's. So
  // each room's leaves measure few pairs in the other. Measured: the two rooms 2.07 times the
  // pairs of the lower one alone, 2.35 times without the test. Each room's light stays the same
  // as with the other room away.
  const auto scene = [](bool upper_room) {
    Scene s = lit_room_and(Vec3(0, 0, 1.1), Vec3(1, 1, 2.1), upper_room);
    if (upper_room) s.lights.push_back({Vec3(0.5, 0.5, 1.7), Rgb::Ones()});
    return s;
  };
  SolverSettings settings;
  settings.refine_threshold = 0;
  const Solution alone = solve_with(scene(false), settings, kHierarchical);
  const Solution both = solve_with(scene(true), settings, kHierarchical);
  std::cout << "two rooms stacked: " << both.stats.visibility_pairs << " pairs measured, "
            << alone.stats.visibility_pairs << " for the lower room alone\n";
  EXPECT_LT(both.stats.visibility_pairs, 2.15 * alone.stats.visibility_pairs);
  double difference = 0, lit = 0;
  for (const int e : alone.leaves()) {
    const Element& el = alone.elements[e];
    if (el.centroid.z() > 1.05) continue;  // (the marker)
    ASSERT_EQ(el.centroid, both.elements[e].centroid);
    lit = std::max(lit, el.radiosity.maxCoeff());
    difference =
        std::max(difference, (el.radiosity - both.elements[e].radiosity).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(difference, 1e-9 * lit);
}

TEST(HierarchicalSolver, WhatItLeavesOutMovesNoLeafMoreThanItsBound) {
  // The Cornell box, swept to 1e-6 but with faint sources left out up to 3% of its mean
  // radiosity: what a patch's links leave out may bring it at most left_out_bound of
  // irradiance (each source's form factor bounded by its bounding sphere's from the patch's,
  // times its brightest leaf). Left in (the same links and more, the rows scaled back to 1
  // aside), the solution moves by at
  // most rho_max / (1 - rho_max) times it (a Neumann series of the left-out term), plus both
  // solves' own bounds. Measured: moved 0.0046 against a bound of 0.105, of which the solves'
  // own bounds are 4e-5.
  const Scene scene = load_scene(kScenes / "cornell-box/scene.json");
  SolverSettings settings;
  settings.patch_size = 0.16;
  settings.refine_threshold = 0;  // the same leaves
  settings.unshot_fraction = 1e-6;
  settings.faint_share = 3e4;  // sources left out up to 3% of the mean radiosity
  const Solution deferred = solve_with(scene, settings, kHierarchical);
  settings.faint_share = 0;
  const Solution linked = solve_with(scene, settings, kHierarchical);
  ASSERT_EQ(deferred.leaves(), linked.leaves());
  EXPECT_GT(deferred.stats.left_out, 0);
  EXPECT_LT(deferred.stats.links, linked.stats.links);
  double rho = 0;
  for (const Material& m : scene.materials) rho = std::max(rho, m.reflectance.maxCoeff());
  double moved = 0;
  for (const int e : deferred.leaves()) {
    moved = std::max(
        moved,
        (deferred.elements[e].radiosity - linked.elements[e].radiosity).cwiseAbs().maxCoeff());
  }
  const double bound = rho / (1 - rho) * deferred.stats.left_out_bound +
                       deferred.stats.error_bound.maxCoeff() + linked.stats.error_bound.maxCoeff();
  std::cout << "Cornell box, faint sources left out: " << deferred.stats.left_out << " ("
            << deferred.stats.links << " links against " << linked.stats.links
            << "); leaves moved by " << moved << ", bound " << bound << "\n";
  EXPECT_LE(moved, bound);
}

TEST(HierarchicalSolver, SameBytesForAnyThreadCount) {
  const Scene scene = load_scene(kScenes / "cornell-box/scene.json");
  SolverSettings settings;
  settings.patch_size = 0.16;
  settings.refine_passes = 1;  // (one pass: 467 leaves split, links handed down, sources opened)
  const Solution all = solve_with(scene, settings, kHierarchical);
  Solution one;
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = solve_with(scene, settings, kHierarchical);
  }
  ASSERT_EQ(all.elements.size(), one.elements.size());
  for (size_t e = 0; e < all.elements.size(); ++e) {
    ASSERT_EQ(all.elements[e].radiosity, one.elements[e].radiosity) << "element " << e;
  }
  EXPECT_EQ(all.stats.links, one.stats.links);
  EXPECT_EQ(all.stats.error_bound, one.stats.error_bound);
}

TEST(HierarchicalSolver, NamesWhatItDoesNotCarryYet) {
  Scene scene = load_scene(kScenes / "closed-cube/scene.json");
  EXPECT_EQ(hierarchical_unsupported(scene), "");
  Scene lit = scene;
  lit.lights.push_back({Vec3(0.5, 0.5, 0.5), Rgb::Ones()});
  EXPECT_EQ(hierarchical_unsupported(lit), "");
  Scene pane = scene;
  pane.materials[0].transmittance = Rgb::Constant(0.2);
  pane.materials[0].reflectance = Rgb::Constant(0.3);
  EXPECT_EQ(hierarchical_unsupported(pane), "filters (transmitting materials)");
  Scene mirror = scene;
  mirror.materials[0].specular = Rgb::Constant(0.5);
  mirror.materials[0].reflectance = Rgb::Constant(0.3);
  EXPECT_EQ(hierarchical_unsupported(mirror), "mirrors and glossy surfaces");
  const RayCaster caster(pane);
  SolverSettings settings;
  settings.method = kHierarchical;
  EXPECT_THROW(solve(caster, settings), Error);
}

}  // namespace
}  // namespace rad
