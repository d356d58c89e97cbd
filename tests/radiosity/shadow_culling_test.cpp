// The solver's shadow culling is sound: where it says nothing can hide a shooter from a point,
// no segment from the point to the shooter meets another polygon (an exact double-precision
// segment test, independent of the shaft); and it does cull, and keeps what is really blocked.
#include "radiosity/shadow_culling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <optional>
#include <random>

#include "geometry/lambert.h"
#include "radiosity/mesher.h"
#include "radiosity/shooter.h"
#include "scene/ray_caster.h"
#include "tests/random_scenes.h"
#include "tests/scene_builder.h"

namespace rad {
namespace {

/// Whether segment x-y crosses polygon p's plane strictly between its ends at a point inside
/// p (even-odd rule in the plane).
bool segment_crosses(const Polygon& p, const Vec3& x, const Vec3& y) {
  const Vec3& o = p.vertices.front();
  const double sx = p.normal.dot(x - o), sy = p.normal.dot(y - o);
  if (!(sx * sy < 0)) return false;
  const Vec3 q = x + sx / (sx - sy) * (y - x);
  const Vec3 u = p.normal.unitOrthogonal(), v = p.normal.cross(u);
  const Vec2 q2(u.dot(q), v.dot(q));
  bool inside = false;
  for (size_t i = 0, j = p.vertices.size() - 1; i < p.vertices.size(); j = i++) {
    const Vec2 a(u.dot(p.vertices[i]), v.dot(p.vertices[i]));
    const Vec2 b(u.dot(p.vertices[j]), v.dot(p.vertices[j]));
    if ((a.y() > q2.y()) != (b.y() > q2.y()) &&
        q2.x() < (b.x() - a.x()) * (q2.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

/// A point of the convex outline from barycentric-like weights.
Vec3 point_in(const std::vector<Vec3>& corners, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  Vec3 sum = Vec3::Zero();
  double total = 0;
  for (const Vec3& c : corners) {
    const double w = std::pow(u(rng), 3);
    sum += w * c, total += w;
  }
  return sum / total;
}

/// A random receiver point and shooter on two polygons, for trial number `trial`: a fifth of
/// the points at a corner or an edge's midpoint of the receiver, where the methods fail. None
/// when both patches lie on one polygon.
struct PointAndShooter {
  const Patch* receiver;
  const Patch* shooter;
  Vec3 x;
};
std::optional<PointAndShooter> random_pair(const std::vector<Patch>& patches, int trial,
                                           std::mt19937_64& rng) {
  const Patch& receiver = patches[rng() % patches.size()];
  const Patch& shooter = patches[rng() % patches.size()];
  if (receiver.polygon == shooter.polygon) return std::nullopt;
  Vec3 x = point_in(receiver.corners, rng);
  const size_t k = receiver.corners.size();
  if (trial % 10 == 0) x = receiver.corners[rng() % k];
  if (trial % 10 == 1) {
    const size_t i = rng() % k;
    x = 0.5 * (receiver.corners[i] + receiver.corners[(i + 1) % k]);
  }
  return PointAndShooter{&receiver, &shooter, x};
}

TEST(ShadowCulling, WhatItCullsNoPolygonHides) {
  std::mt19937_64 rng(5);
  long culled = 0, kept = 0, kept_and_blocked = 0, violations = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    test::RandomSceneMaker maker(seed);
    const Scene scene = maker.random_scene().scene;
    const ShadowCulling culling(scene, 1e-9);
    const std::vector<Patch> patches = make_patches(scene, 0.4);
    for (int trial = 0; trial < 300; ++trial) {
      const Patch& receiver = patches[rng() % patches.size()];
      const Patch& shooter = patches[rng() % patches.size()];
      if (receiver.polygon == shooter.polygon) continue;
      const Vec3 x = point_in(receiver.corners, rng);
      const bool hidden =
          culling.may_be_hidden(x, receiver.polygon, shooter.corners, shooter.polygon);
      (hidden ? kept : culled) += 1;
      bool blocked = false;
      for (int k = 0; k < 60 && !blocked; ++k) {
        const Vec3 y = k < static_cast<int>(shooter.corners.size())
                           ? shooter.corners[k]
                           : point_in(shooter.corners, rng);
        for (size_t p = 0; p < scene.polygons.size() && !blocked; ++p) {
          if (static_cast<int>(p) == receiver.polygon || static_cast<int>(p) == shooter.polygon)
            continue;
          blocked = segment_crosses(scene.polygons[p], x, y);
        }
      }
      kept_and_blocked += hidden && blocked;
      if (!hidden && blocked && ++violations <= 3) {
        ADD_FAILURE() << "seed " << seed << ": x " << x.transpose() << " on polygon "
                      << receiver.polygon << ", shooter on polygon " << shooter.polygon
                      << " culled, but a segment to it is blocked";
      }
    }
  }
  EXPECT_EQ(violations, 0);
  EXPECT_GT(culled, kept / 4) << "culled " << culled << ", kept " << kept;
  EXPECT_GT(kept_and_blocked, kept / 10) << "of " << kept;
}

TEST(ShadowCulling, ARayToTheShootersCentreStandsForTheScanOnlyWhenTheScanAgrees) {
  // Shooter::something_on_the_way is the solver's shortcut for a long scan: a polygon on the
  // segment to the shooter's centre means may_be_hidden is true. Were it ever true where the
  // scan says false, the solver would cast rays where it cast none before and its results
  // would move; so the implication is checked here on random scenes (convex, concave,
  // interpenetrating, coplanar), with receiver points on edges and corners too, at the pad the
  // solver uses, and the scan with the shortcut must give the scan's answer.
  std::mt19937_64 rng(11);
  long shortcut = 0, scanned = 0, violations = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    test::RandomSceneMaker maker(seed);
    const Scene scene = maker.random_scene().scene;
    const RayCaster caster(scene);
    const double epsilon = 1e-5 * scene.bounds().diagonal();
    const Shooter shooter_rays(caster, SolverSettings{}, epsilon);
    const ShadowCulling culling(scene, epsilon);
    const std::vector<Patch> patches = make_patches(scene, 0.4);
    for (int trial = 0; trial < 400; ++trial) {
      const std::optional<PointAndShooter> pair = random_pair(patches, trial, rng);
      if (!pair) continue;
      const Patch &receiver = *pair->receiver, &shooter = *pair->shooter;
      const Vec3& x = pair->x;
      const bool on_the_way = shooter_rays.something_on_the_way(x, receiver.polygon, shooter);
      const bool hidden =
          culling.may_be_hidden(x, receiver.polygon, shooter.corners, shooter.polygon);
      EXPECT_EQ(culling.may_be_hidden(x, receiver.polygon, shooter.corners, shooter.polygon,
                                      [&] { return on_the_way; }),
                hidden);
      shortcut += on_the_way;
      scanned += !on_the_way && hidden;
      if (on_the_way && !hidden && ++violations <= 3) {
        ADD_FAILURE() << "seed " << seed << ": x " << x.transpose() << " on polygon "
                      << receiver.polygon << ", shooter on polygon " << shooter.polygon
                      << ": a polygon on the way, but the scan finds none that may hide it";
      }
    }
  }
  EXPECT_EQ(violations, 0);
  // Both answers occur: the shortcut takes many pairs, and leaves others to the scan.
  EXPECT_GT(shortcut, 200);
  EXPECT_GT(scanned, 50);
}

/// Whether some polygon other than the receiver's and the shooter's crosses segment x-y.
bool blocked_by_any(const Scene& scene, const Vec3& x, const Vec3& y, int receiver, int shooter) {
  for (size_t p = 0; p < scene.polygons.size(); ++p) {
    if (static_cast<int>(p) == receiver || static_cast<int>(p) == shooter) continue;
    if (segment_crosses(scene.polygons[p], x, y)) return true;
  }
  return false;
}

TEST(ShadowCulling, APolygonSaidToHideAllOfAShooterBlocksEverySegmentToIt) {
  // Shooter::hides_all lets the solver skip the rays of a pair one polygon hides whole. Where
  // it says so, every segment from the point to the shooter (its corners and 60 points inside)
  // must cross some polygon by the exact segment test above, and the rays (culling off: no
  // shortcut) must find nothing visible. Random scenes (convex, concave, interpenetrating,
  // coplanar), receiver points at corners and edges too; and where the polygon on the way does
  // not hide it all, some pairs have a segment passing (the test would see a claim too many).
  std::mt19937_64 rng(17);
  long hidden = 0, partly = 0, violations = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    test::RandomSceneMaker maker(seed);
    const Scene scene = maker.random_scene().scene;
    const RayCaster caster(scene);
    const double epsilon = 1e-5 * scene.bounds().diagonal();
    const Shooter with_shortcut(caster, SolverSettings{}, epsilon);
    SolverSettings rays_only;
    rays_only.shaft_culling = false;
    const Shooter all_rays(caster, rays_only, epsilon);
    const std::vector<Patch> patches = make_patches(scene, 0.4);
    for (int trial = 0; trial < 2000; ++trial) {
      const std::optional<PointAndShooter> pair = random_pair(patches, trial, rng);
      if (!pair) continue;
      const Patch &receiver = *pair->receiver, &shooter = *pair->shooter;
      const Vec3& x = pair->x;
      int blocker = -1;
      if (!with_shortcut.something_on_the_way(x, receiver.polygon, shooter, &blocker)) continue;
      std::vector<Vec3> ends = shooter.corners;
      for (int j = 0; j < 60; ++j) ends.push_back(point_in(shooter.corners, rng));
      bool all_blocked = true;
      for (const Vec3& y : ends)
        all_blocked &= blocked_by_any(scene, x, y, receiver.polygon, shooter.polygon);
      if (!with_shortcut.hides_all(x, shooter, blocker)) {
        partly += !all_blocked;
        continue;
      }
      ++hidden;
      const Rgb rays = all_rays.visible_form_factor(x, receiver.normal, receiver.polygon, shooter,
                                                    static_cast<uint64_t>(trial));
      if ((!all_blocked || rays != Rgb::Zero()) && ++violations <= 3) {
        ADD_FAILURE() << "seed " << seed << ": x " << x.transpose() << " on polygon "
                      << receiver.polygon << ", shooter on polygon " << shooter.polygon
                      << " said hidden whole by polygon " << blocker << ", but "
                      << (all_blocked ? "the rays see " + std::to_string(rays.maxCoeff())
                                      : std::string("a segment passes"));
      }
    }
  }
  EXPECT_EQ(violations, 0);
  EXPECT_GT(hidden, 200) << "pairs hidden whole";
  std::cout << hidden << " pairs hidden whole, " << partly << " with a segment passing by\n";
  EXPECT_GT(partly, 100) << "pairs with a polygon on the way and a segment passing beside it";
}

TEST(ShadowCulling, AWallHidesAShooterWholeOnlyWhereItCoversItsCornersFromThePoint) {
  // The point at the origin, a 2 x 2 shooter 2 above it facing down, and between them at
  // height 1 a square wall of half-width w: seen from the point, the shooter's corners cross
  // the wall's plane at (+-0.5, +-0.5), so the wall hides it whole when w > 0.5 (by more than
  // epsilon), and not when w < 0.5 (the rays then pass by its edges); nor when the wall is a
  // filter, nor when the point lies in the wall's plane.
  for (const double w : {0.4, 0.499, 0.501, 0.6, 3.0}) {
    for (const bool filter : {false, true}) {
      test::SceneBuilder b;
      const int grey = b.material("grey", Rgb::Constant(0.5), Rgb::Zero());
      const int pane = b.material("pane", Rgb::Zero(), Rgb::Zero(), Rgb::Constant(0.5));
      const int floor = b.rectangle(-3, 3, -3, 3, 0, false, grey);
      const int wall = b.rectangle(-w, w, -w, w, 1, true, filter ? pane : grey);
      b.rectangle(-1, 1, -1, 1, 2, true, grey);
      const RayCaster caster(b.scene());
      const Shooter rays(caster, SolverSettings{}, 1e-6);
      const std::vector<Patch> patches = make_patches(b.scene(), 10);
      const Patch& shooter = patches.back();
      ASSERT_EQ(shooter.polygon, 2);
      const bool hides = rays.hides_all(Vec3(0, 0, 0), shooter, wall);
      EXPECT_EQ(hides, w > 0.5 && !filter) << "w " << w << (filter ? ", a filter" : "");
      EXPECT_FALSE(rays.hides_all(Vec3(0, 0, 1), shooter, wall)) << "x in the wall's plane";
      // The solver's path agrees: none visible where it hides all, some where it does not
      // (away from w = 0.5, where the rays past the edge are too few to be sure of one).
      if (std::abs(w - 0.5) < 0.05) continue;
      const Rgb ff = rays.visible_form_factor(Vec3(0, 0, 0), Vec3(0, 0, 1), floor, shooter, 7);
      EXPECT_EQ(ff == Rgb::Zero(), w > 0.5 && !filter) << "w " << w;
    }
  }
}

TEST(ShadowCulling, APolygonSaidToHideAHullFromAHullCrossesEverySegmentBetweenThem) {
  // Shooter::hides_between lets the hierarchical solver drop a cluster or a patch one polygon
  // hides from the whole of a receiver (or from its centroid, when that is all that gathers).
  // Where it says so, the polygon itself must cross every segment from a point of the receiver
  // (its corners and 30 points inside; or the centroid) to a point of the
  // source's box (its corners and 30 points inside), by the exact segment test above. Random
  // scenes, every polygon tried as the blocker; and where a polygon's plane parts the two but
  // some segment passes beside it, it must say no (the test counts those, so that a claim
  // made on the planes alone would be seen).
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0, 1);
  long hidden = 0, beside = 0, violations = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    test::RandomSceneMaker maker(seed);
    const Scene scene = maker.random_scene().scene;
    const RayCaster caster(scene);
    const Shooter rays(caster, SolverSettings{}, 1e-5 * scene.bounds().diagonal());
    const std::vector<Patch> patches = make_patches(scene, 0.4);
    for (int trial = 0; trial < 2000; ++trial) {
      const Patch& receiver = patches[rng() % patches.size()];
      const Patch& source = patches[rng() % patches.size()];
      const bool whole = trial % 2 == 0;
      if (receiver.polygon == source.polygon) continue;
      Eigen::AlignedBox3d box;
      for (const Vec3& c : source.corners) box.extend(c);
      std::vector<Vec3> to;
      for (int k = 0; k < 8; ++k) to.push_back(box.corner(Eigen::AlignedBox3d::CornerType(k)));
      Vec3 centroid = Vec3::Zero();
      for (const Vec3& c : receiver.corners) centroid += c / receiver.corners.size();
      std::vector<Vec3> from = whole ? receiver.corners : std::vector<Vec3>{centroid};
      std::vector<Vec3> inside_from = from, inside_to = to;
      for (int j = 0; j < 30; ++j) {
        if (whole) inside_from.push_back(point_in(receiver.corners, rng));
        inside_to.push_back(box.min() + box.sizes().cwiseProduct(Vec3(u(rng), u(rng), u(rng))));
      }
      for (size_t b = 0; b < scene.polygons.size(); ++b) {
        const Polygon& blocker = scene.polygons[b];
        const auto height = [&](const Vec3& y) {
          return blocker.normal.dot(y - blocker.vertices[0]);
        };
        const double side = height(from[0]);
        const bool parted =
            std::all_of(from.begin(), from.end(),
                        [&](const Vec3& a) { return height(a) * side > 0; }) &&
            std::all_of(to.begin(), to.end(), [&](const Vec3& y) { return height(y) * side < 0; });
        if (!parted) continue;
        bool all_cross = true;
        for (const Vec3& a : inside_from) {
          for (const Vec3& y : inside_to) all_cross &= segment_crosses(blocker, a, y);
        }
        if (!rays.hides_between(from, to, static_cast<int>(b))) {
          beside += !all_cross;
          continue;
        }
        ++hidden;
        if (!all_cross && ++violations <= 3) {
          ADD_FAILURE() << "seed " << seed << ": polygon " << b << " said to hide the box of "
                        << "polygon " << source.polygon << "'s patch from polygon "
                        << receiver.polygon << "'s, but a segment passes beside it";
        }
      }
    }
  }
  EXPECT_EQ(violations, 0);
  std::cout << hidden << " hulls hidden whole, " << beside << " parted with a segment beside\n";
  EXPECT_GT(hidden, 100) << "hulls hidden whole";
  EXPECT_GT(beside, 100) << "hulls a plane parts with a segment passing beside the polygon";
}

TEST(ShadowCulling, AWallHidesABoxFromASquareOnlyWhereItCoversEveryCrossing) {
  // The square [-0.5, 0.5]^2 at height 0, the box [-1, 1]^2 x [2, 3] above it, and between
  // them at height 1 a square wall of half-width w. The segments' crossings of the wall's plane
  // reach farthest from the square's corner (0.5, 0.5) to the box's lower corner (1, 1, 2):
  // 0.5 + (1 - 0.5) / 2 = 0.75 (to the upper corner: 0.5 + 0.5 / 3 = 0.67). So the wall hides
  // the box from the square when w > 0.75 and not when w < 0.75; nor when the wall is a
  // filter, nor when a point of the square lies in its plane or the box reaches through it.
  const std::vector<Vec3> square{{-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0.5, 0.5, 0}, {-0.5, 0.5, 0}};
  const auto box_corners = [](double bottom) {
    std::vector<Vec3> corners;
    for (int k = 0; k < 8; ++k)
      corners.emplace_back(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 3 : bottom);
    return corners;
  };
  for (const double w : {0.7, 0.749, 0.751, 0.8, 3.0}) {
    for (const bool filter : {false, true}) {
      test::SceneBuilder b;
      const int grey = b.material("grey", Rgb::Constant(0.5), Rgb::Zero());
      const int pane = b.material("pane", Rgb::Zero(), Rgb::Zero(), Rgb::Constant(0.5));
      b.rectangle(-3, 3, -3, 3, 0, false, grey);
      const int wall = b.rectangle(-w, w, -w, w, 1, true, filter ? pane : grey);
      const RayCaster caster(b.scene());
      const Shooter rays(caster, SolverSettings{}, 1e-6);
      EXPECT_EQ(rays.hides_between(square, box_corners(2), wall), w > 0.75 && !filter)
          << "w " << w << (filter ? ", a filter" : "");
      std::vector<Vec3> touching = square;
      touching[2].z() = 1;
      EXPECT_FALSE(rays.hides_between(touching, box_corners(2), wall)) << "a point in its plane";
      EXPECT_FALSE(rays.hides_between(square, box_corners(0.5), wall)) << "the box through it";
    }
  }
}

TEST(ShadowCulling, PastItsCapTheScanLeavesThePairToTheRaysWhichLetAllThrough) {
  // A point on a floor and a small lamp above it to the side; beside the shaft between them,
  // inside its box, a crowd of small upright triangles whose planes do not part the point from
  // the lamp (each one the scan must look at, none in the way). Below the scan's cap it clears
  // the pair; above it, it gives up ("may be hidden", always safe), and the shadow rays then
  // find what the scan would have: the lamp's whole form factor, the same double.
  for (const int crowd : {200, 300}) {
    test::SceneBuilder b;
    const int grey = b.material("grey", Rgb::Constant(0.5), Rgb::Zero());
    const int floor = b.rectangle(-0.5, 0.5, -0.5, 0.5, 0, false, grey);
    const int lamp = b.rectangle(1.9, 2.1, -0.1, 0.1, 2, true, grey);
    for (int k = 0; k < crowd; ++k) {
      const double x0 = 1.0 + 0.003 * k, y = 0.05;
      b.polygon({{x0, y, 0.2}, {x0 + 0.05, y, 0.2}, {x0, y, 0.25}}, grey);
    }
    const Scene& scene = b.scene();
    const double epsilon = 1e-5 * scene.bounds().diagonal();
    const ShadowCulling culling(scene, epsilon);
    Patch shooter;
    shooter.polygon = lamp;
    shooter.corners = scene.polygons[lamp].vertices;
    shooter.normal = scene.polygons[lamp].normal;
    shooter.area = 0.04;
    const Vec3 x(0, 0, 0), up(0, 0, 1);
    EXPECT_EQ(culling.may_be_hidden(x, floor, shooter.corners, lamp), crowd > 256)
        << crowd << " triangles beside the shaft";
    const RayCaster caster(scene);
    const Shooter rays(caster, SolverSettings{}, epsilon);
    const double whole = unblocked_form_factor(x, up, shooter.corners, shooter.normal);
    EXPECT_GT(whole, 0);
    EXPECT_EQ(rays.visible_form_factor(x, up, floor, shooter, 7), Rgb::Constant(whole))
        << crowd << " triangles beside the shaft";
  }
}

TEST(ShadowCulling, TheReachOfASphereBoundsTheFormFactorOfAllThatLiesInIt) {
  // sphere_form_factor_bound against Lambert's exact formula, from points of random triangles
  // (corners, centroid, inside) to what lies in random spheres on both sides of the triangle's
  // horizon: the 64-gon inscribed in the sphere's silhouette from the point (nearly all the
  // sphere shows it) and random triangles inside it. The silhouettes make the test sharp:
  // above the receiver the bound is within a few per cent of them, and a bound that forgot
  // the part of a sphere reaching above the horizon would read 0 where they see light.
  std::mt19937_64 rng(46);
  std::uniform_real_distribution<double> u(-1, 1), unit(0, 1);
  const auto random_unit = [&] {
    Vec3 v;
    do v = Vec3(u(rng), u(rng), u(rng));
    while (!(v.norm() > 0.1 && v.norm() < 1));
    return Vec3(v.normalized());
  };
  int points = 0, sharp = 0, straddling = 0;
  double worst = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 n = random_unit();
    const Vec3 a = n.unitOrthogonal(), b = n.cross(a);
    const double scale = std::pow(10.0, -3 * unit(rng));  // 1e-3 to 1
    std::vector<Vec3> triangle;
    for (int k = 0; k < 3; ++k) triangle.push_back(scale * (u(rng) * a + u(rng) * b));
    const Vec3 centroid = (triangle[0] + triangle[1] + triangle[2]) / 3;
    const Sphere receiver = bounding_sphere(triangle, centroid);
    // Sources over the whole sky, a third of them straddling the horizon.
    Sphere source{3 * Vec3(u(rng), u(rng), u(rng)), std::pow(10.0, -2 * unit(rng))};
    if (trial % 3 == 0) source.centre += (0.5 * u(rng) * source.radius - n.dot(source.centre)) * n;
    const double bound = sphere_form_factor_bound(receiver, n, source);
    std::vector<Vec3> at = triangle;
    at.push_back(centroid);
    for (int k = 0; k < 3; ++k) at.push_back(point_in(triangle, rng));
    for (const Vec3& x : at) {
      const Vec3 w = source.centre - x;
      const double d = w.norm();
      if (!(d > source.radius * (1 + 1e-6))) continue;
      ++points;
      // The silhouette from x: the circle of radius r cos(alpha) at d cos^2(alpha) along w.
      const double sine = source.radius / d, cosine = std::sqrt(1 - sine * sine);
      const Vec3 axis = w / d, p = axis.unitOrthogonal(), q = axis.cross(p);
      std::vector<Vec3> silhouette;
      for (int k = 0; k < 64; ++k) {
        const double t = 2 * std::numbers::pi * k / 64;
        silhouette.push_back(x + d * cosine * cosine * axis +
                             source.radius * cosine * (std::cos(t) * p + std::sin(t) * q));
      }
      std::vector<Vec3> inside;
      for (int k = 0; k < 3; ++k)
        inside.push_back(source.centre + source.radius * unit(rng) * random_unit());
      const double seen = point_polygon_form_factor(x, n, silhouette);
      const double inner = point_polygon_form_factor(x, n, inside);
      EXPECT_LE(seen, bound * (1 + 1e-9) + 1e-15) << "trial " << trial;
      EXPECT_LE(inner, bound * (1 + 1e-9) + 1e-15) << "trial " << trial;
      if (bound > 0) worst = std::max(worst, seen / bound);
      if (seen > 0.9 * bound && bound > 0) ++sharp;
      if (std::abs(n.dot(source.centre - centroid)) < source.radius && seen > 0) ++straddling;
    }
  }
  std::cout << points << " points, " << sharp << " within 10% of the bound, " << straddling
            << " seeing a sphere across the horizon; largest share of the bound seen " << worst
            << "\n";
  EXPECT_GT(points, 10000);
  EXPECT_GT(sharp, 100);
  EXPECT_GT(straddling, 1000);
}

}  // namespace
}  // namespace rad
