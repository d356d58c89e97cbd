// Plane mirrors (paper 000 §3) through the local pass: against Howell's closed forms, the
// furnace in a cube with a mirror face, a hand-built unfolded scene gathered by the opaque
// code at the real receiver, and the same values with and without the culling beams (000 §5).
#include <gtest/gtest.h>

#include <array>
#include <random>

#include "hemisphere/hemisphere_gatherer.h"
#include "localpass/local_pass.h"
#include "radiosity/solution_faces.h"
#include "radiosity/solver.h"
#include "reference/monte_carlo.h"
#include "scene/polygon_faces.h"
#include "scene/polygon_validation.h"
#include "scene/ray_caster.h"
#include "specular/mirror_images.h"
#include "tests/closed_forms.h"
#include "tests/rgb_checks.h"
#include "tests/scene_builder.h"
#include "vertex/vertex_tracer.h"

namespace rad {
namespace {

using test::agree;
using test::SceneBuilder;

constexpr Method kExact[] = {Method::hemisphere, Method::vertex};

/// Direct light at x, with the mirrors to `depth` (the polygons radiate their emission).
LocalPassResult direct(const Scene& scene, Method method, const Vec3& x, const Vec3& n,
                       int depth = 2, bool culling = true) {
  LocalPassSettings settings;
  settings.mirror_depth = depth;
  settings.mirror_culling = culling;
  return LocalPass(scene, faces_from_polygons(scene), method, settings).gather(x, n, 0);
}

/// A rectangle in the plane x = at, y in [y0, y1], z in [z0, z1], front towards -x or +x.
int wall_x(SceneBuilder& b, double at, double y0, double y1, double z0, double z1,
           bool facing_minus_x, int material) {
  if (facing_minus_x)
    return b.polygon({{at, y0, z0}, {at, y0, z1}, {at, y1, z1}, {at, y1, z0}}, material);
  return b.polygon({{at, y0, z0}, {at, y1, z0}, {at, y1, z1}, {at, y0, z1}}, material);
}

TEST(Mirror, WallMirrorBesideACeilingLampIsSpecularTimesHowell) {
  // x at the origin on the floor, a lamp at z = 3 over x in [-1, 1.9], a mirror in the plane
  // x = 2 up to z = 2.5. From x' = (4, 0, 0) the mirror's top edge, parallel to y, cuts the
  // lamp along x = 4 - 2 * 3 / 2.5 = 1.6: the lamp seen in the mirror is the rectangle
  // [-1, 1.6] x [-0.5, 0.8], at offsets [-5, -2.4] from x'. H = E (F_direct + s F_image).
  const Rgb s(0.9, 0.8, 0.7), e(1, 2, 3);
  SceneBuilder b;
  b.rectangle(-3, 1.5, -3, 3, 0, false, b.material("floor", Rgb::Constant(0.5), Rgb::Zero()));
  b.rectangle(-1, 1.9, -0.5, 0.8, 3, true, b.material("lamp", Rgb::Zero(), e));
  const int mirror = wall_x(b, 2, -10, 10, 0, 2.5, true,
                            b.material("mirror", Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), s));
  ASSERT_LT(b.scene().polygons[mirror].normal.x(), -0.99) << "the mirror must face x";
  const double f_direct = test::howell_rectangle(-1, 1.9, -0.5, 0.8, 3);
  const double f_image = test::howell_rectangle(-5, -2.4, -0.5, 0.8, 3);
  for (const Method method : kExact) {
    const LocalPassResult r = direct(b.scene(), method, Vec3::Zero(), Vec3::UnitZ());
    EXPECT_TRUE(agree(r.irradiance, e * f_direct + e.cwiseProduct(s) * f_image))
        << method_name(method);
    EXPECT_EQ(r.mirrored, 1) << method_name(method);
    // Without mirrors: the lamp alone.
    EXPECT_TRUE(
        agree(direct(b.scene(), method, Vec3::Zero(), Vec3::UnitZ(), 0).irradiance, e * f_direct));
  }
}

/// The unit cube [0, 1]^3 with every face's front inside; `mirrors` lists faces (0: z = 0,
/// 1: z = 1, 2: x = 0, 3: x = 1, 4: y = 0, 5: y = 1) that are mirrors of reflectance s,
/// black; the others radiate 2 (B = E / (1 - rho) for E = 1, rho = 0.5: the furnace).
Scene cube(const std::vector<int>& mirrors, double s) {
  SceneBuilder b;
  const int diffuse = b.material("furnace", Rgb::Constant(0.5), Rgb::Constant(2));
  const int mirror = b.material("mirror", Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Constant(s));
  const auto m = [&](int face) {
    return std::find(mirrors.begin(), mirrors.end(), face) != mirrors.end() ? mirror : diffuse;
  };
  b.rectangle(0, 1, 0, 1, 0, false, m(0));
  b.rectangle(0, 1, 0, 1, 1, true, m(1));
  wall_x(b, 0, 0, 1, 0, 1, false, m(2));
  wall_x(b, 1, 0, 1, 0, 1, true, m(3));
  b.polygon({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, m(4));
  b.polygon({{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}}, m(5));
  for (const Polygon& p : b.scene().polygons) {
    const Vec3 centre = 0.5 * (p.vertices[0] + p.vertices[2]);
    EXPECT_LT((centre + 0.5 * p.normal - Vec3::Constant(0.5)).norm(), 1e-12)
        << "cube faces must face in";
  }
  return b.scene();
}

/// Seeded points on the cube's faces that are not mirrors, with their inward normals.
std::vector<std::pair<Vec3, Vec3>> cube_points(const Scene& scene, int count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.02, 0.98);
  std::vector<std::pair<Vec3, Vec3>> points;
  while (static_cast<int>(points.size()) < count) {
    const Polygon& p = scene.polygons[static_cast<size_t>(u(rng) * 6) % 6];
    if (scene.materials[p.material].is_mirror()) continue;
    const Vec3 a = p.vertices[1] - p.vertices[0], c = p.vertices[3] - p.vertices[0];
    points.push_back({p.vertices[0] + u(rng) * a + u(rng) * c, p.normal});
  }
  return points;
}

TEST(Mirror, FurnaceCubeWithAPerfectMirrorFaceIsTwoEverywhere) {
  // The mirror shows the room, which radiates 2 everywhere: H = 2 at every diffuse point.
  const Scene scene = cube({3}, 1.0);
  for (const Method method : kExact) {
    int mirrored = 0;
    for (const auto& [x, n] : cube_points(scene, 12, 5)) {
      const LocalPassResult r = direct(scene, method, x, n);
      EXPECT_TRUE(agree(r.irradiance, Rgb::Constant(2)))
          << method_name(method) << " at " << x.transpose();
      mirrored += r.mirrored > 0;
    }
    EXPECT_GT(mirrored, 6);
  }
}

TEST(Mirror, TwoFacingMirrorsConvergeGeometricallyWithTheDepth) {
  // Mirrors at x = 0 and x = 1, reflectance 0.5: each further reflection adds at most 2 s^d,
  // and less each time; the corner of two perpendicular perfect mirrors (x = 1, y = 1) needs
  // depth 2 for the furnace value, and its two depth-2 images, which coincide, count once.
  const Scene facing = cube({2, 3}, 0.5);
  const auto points = cube_points(facing, 4, 6);
  for (const auto& [x, n] : points) {
    std::vector<double> h;
    for (int depth = 0; depth <= 5; ++depth)
      h.push_back(direct(facing, Method::vertex, x, n, depth).irradiance.x());
    for (int d = 1; d <= 5; ++d) {
      const double step = h[d] - h[d - 1];
      EXPECT_GT(step, 0) << "depth " << d << " at " << x.transpose();
      EXPECT_LE(step, 2 * std::pow(0.5, d) + 1e-12) << "depth " << d << " at " << x.transpose();
      if (d >= 2) {
        EXPECT_LT(step, h[d - 1] - h[d - 2]) << "depth " << d;
      }
    }
  }
  const Scene corner = cube({3, 5}, 1.0);
  for (const auto& [x, n] : cube_points(corner, 8, 7)) {
    for (const Method method : kExact) {
      EXPECT_TRUE(agree(direct(corner, method, x, n, 2).irradiance, Rgb::Constant(2)))
          << method_name(method) << " at " << x.transpose();
    }
  }
}

/// A lamp over a floor, a wall mirror at x = 2 (diffuse too), a blocker on each leg: one under
/// the lamp's light to the mirror, one standing between the floor and the mirror.
Scene mirror_room(const Rgb& specular) {
  SceneBuilder b;
  const int grey = b.material("grey", Rgb::Constant(0.5), Rgb::Zero());
  b.rectangle(-3, 1.5, -3, 3, 0, false, grey);
  b.rectangle(-1, 1.9, -0.5, 0.8, 3, true, b.material("lamp", Rgb::Zero(), Rgb(1, 2, 3)));
  b.rectangle(1.2, 1.8, -0.3, 0.4, 2, false, grey);  // on the second leg
  wall_x(b, 1.7, -1, 0.2, 0.2, 1.2, true, grey);     // on the first leg
  wall_x(b, 2, -2, 2, 0, 2.5, true,
         b.material("mirror", Rgb::Constant(0.05), Rgb::Zero(), Rgb::Zero(), specular));
  return b.scene();
}

/// 000 Fig. 3a built by hand: the real polygons, their mirror images behind x = 2 radiating
/// specular x emission, and a black frame around the mirror's outline; the mirror removed.
Scene hand_unfolded(const Scene& room, const Rgb& specular) {
  Scene out = room;
  out.polygons.pop_back();  // the mirror: an open hole now
  std::vector<std::string> warnings;
  const int count = static_cast<int>(room.materials.size());
  for (int m = 0; m < count; ++m) {
    Material image = room.materials[m];
    image.emission = image.emission.cwiseProduct(specular);
    out.materials.push_back(image);
  }
  const int black = static_cast<int>(out.materials.size());
  out.materials.push_back(Material{"frame", Rgb::Zero(), Rgb::Zero()});
  const auto add = [&](std::vector<Vec3> v, int material) {
    for (Polygon& p : make_polygons(std::move(v), "hand-built", material,
                                    static_cast<int>(out.objects.size()), 0, warnings)) {
      out.polygons.push_back(std::move(p));
    }
    out.objects.push_back(SceneObject{});
  };
  for (size_t i = 0; i + 1 < room.polygons.size(); ++i) {
    std::vector<Vec3> image;
    for (auto v = room.polygons[i].vertices.rbegin(); v != room.polygons[i].vertices.rend(); ++v)
      image.push_back(Vec3(4 - v->x(), v->y(), v->z()));  // reflected in x = 2, reversed
    add(image, room.polygons[i].material + count);
  }
  const double l = 100;
  for (const auto& [y0, y1, z0, z1] : std::vector<std::array<double, 4>>{
           {-l, -2, -l, l}, {2, l, -l, l}, {-2, 2, 2.5, l}, {-2, 2, -l, 0}}) {
    add({{2, y0, z0}, {2, y0, z1}, {2, y1, z1}, {2, y1, z0}}, black);
  }
  return out;
}

/// The hand-built scene's irradiance at x on the floor, by the opaque hemisphere gatherer.
Rgb hand_unfolded_irradiance(const Scene& room, const Rgb& s, const Vec3& x) {
  const Scene by_hand = hand_unfolded(room, s);
  return HemisphereGatherer(faces_from_polygons(by_hand), by_hand.tolerance())
      .gather(x, Vec3::UnitZ())
      .irradiance;
}

TEST(Mirror, EqualsTheHandBuiltUnfoldedSceneGatheredAtTheRealReceiver) {
  // Independent of the unfolding: the images are built by hand around the real receiver x, and
  // gathered by the opaque gatherers alone (no local pass, no mirrors).
  const Rgb s(0.9, 0.8, 0.7);
  const Scene room = mirror_room(s), by_hand = hand_unfolded(room, s);
  const HemisphereGatherer hemisphere(faces_from_polygons(by_hand), by_hand.tolerance());
  const VertexTracer vertex(by_hand);
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> ux(-2.9, 1.45), uy(-2.9, 2.9);
  int shadowed = 0;
  for (int i = 0; i < 40; ++i) {
    const Vec3 x(ux(rng), uy(rng), 0);
    const Rgb expected = hemisphere.gather(x, Vec3::UnitZ()).irradiance;
    ASSERT_TRUE(agree(vertex.gather(x, Vec3::UnitZ()).irradiance, expected)) << x.transpose();
    for (const Method method : kExact) {
      EXPECT_TRUE(agree(direct(room, method, x, Vec3::UnitZ()).irradiance, expected))
          << method_name(method) << " at " << x.transpose();
    }
    // How much the blockers took from the reflection (so the legs' blockers took part).
    Scene clear = room;
    clear.polygons.erase(clear.polygons.begin() + 2, clear.polygons.begin() + 4);
    const Rgb unblocked = direct(clear, Method::vertex, x, Vec3::UnitZ()).irradiance;
    const Rgb no_mirror = direct(clear, Method::vertex, x, Vec3::UnitZ(), 0).irradiance;
    const Rgb blocked_direct = direct(room, Method::vertex, x, Vec3::UnitZ(), 0).irradiance;
    shadowed +=
        (unblocked - no_mirror).x() - (expected - blocked_direct).x() > 1e-6 * unblocked.x();
  }
  EXPECT_GT(shadowed, 5);
}

TEST(Mirror, CullingBeamsChangeNothingAndSkipPointsOutsideThem) {
  // A small mirror high on the wall: from most of the floor no lamp shows in it.
  SceneBuilder b;
  b.rectangle(-3, 1.5, -3, 3, 0, false, b.material("grey", Rgb::Constant(0.5), Rgb::Zero()));
  b.rectangle(-1, 0.5, -0.5, 0.8, 3, true, b.material("lamp", Rgb::Zero(), Rgb(1, 2, 3)));
  wall_x(b, 2, 1.0, 1.6, 2.0, 2.6, true,
         b.material("mirror", Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Constant(0.9)));
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> ux(-2.9, 1.45), uy(-2.9, 2.9);
  int culled = 0, lit = 0;
  for (int i = 0; i < 60; ++i) {
    const Vec3 x(ux(rng), uy(rng), 0);
    for (const Method method : kExact) {
      const LocalPassResult with = direct(b.scene(), method, x, Vec3::UnitZ(), 2, true);
      const LocalPassResult without = direct(b.scene(), method, x, Vec3::UnitZ(), 2, false);
      EXPECT_EQ(with.irradiance, without.irradiance) << method_name(method) << x.transpose();
      EXPECT_EQ(without.mirrored, 1);
      culled += with.mirrored == 0;
      const Rgb no_mirror = direct(b.scene(), method, x, Vec3::UnitZ(), 0).irradiance;
      lit += (without.irradiance - no_mirror).maxCoeff() > 0;
    }
  }
  EXPECT_GT(culled, 20);  // the beams did cull
  EXPECT_GT(lit, 10);     // and the mirror did light some points
}

TEST(Mirror, DegenerateReceiversAndMirrors) {
  const Rgb s = Rgb::Constant(0.8);
  const Scene room = mirror_room(s);
  for (const Method method : kExact) {
    // x on the mirror's plane (on the mirror, facing into the room): it sees the mirror
    // edge-on; the direct light alone.
    const Vec3 on_mirror(2, 0.5, 1), facing(-1, 0, 0);
    EXPECT_TRUE(agree(direct(room, method, on_mirror, facing).irradiance,
                      direct(room, method, on_mirror, facing, 0).irradiance));
    // x behind the mirror: its back reflects nothing.
    const Vec3 behind(2.5, 0, 1);
    EXPECT_EQ(direct(room, method, behind, -facing).mirrored, 0);
    // x on the floor right under the mirror's bottom edge, facing up: the image of the floor
    // lies in x's own plane.
    const Vec3 corner(1.5, 0.3, 0);
    EXPECT_TRUE(agree(direct(room, method, corner, Vec3::UnitZ()).irradiance,
                      hand_unfolded_irradiance(room, s, corner)));
  }
}

TEST(Mirror, MonteCarloRaysOffTheMirrorAgreeWithinFourStandardErrors) {
  // The baseline's rays reflect off the mirror (sampled, not unfolded): 8 seeds of 4096 rays
  // at each point against the exact value.
  const Scene room = mirror_room(Rgb(0.9, 0.6, 0.3));
  const MonteCarloGatherer mc(room, faces_from_polygons(room));
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> ux(-2.9, 1.45), uy(-2.9, 2.9);
  int outside = 0;
  for (int i = 0; i < 20; ++i) {
    const Vec3 x(ux(rng), uy(rng), 0);
    const Rgb h = direct(room, Method::vertex, x, Vec3::UnitZ()).irradiance;
    const test::SampledMean m = test::sampled_mean(
        8, [&](int k) { return mc.gather(x, Vec3::UnitZ(), 4096, 100 * i + k); });
    const Rgb &mean = m.mean, &se = m.standard_error;
    for (int c = 0; c < 3; ++c) {
      if (std::abs(mean[c] - h[c]) > 4 * se[c] + 1e-9 * h[c] && ++outside <= 3) {
        ADD_FAILURE() << "at " << x.transpose() << " channel " << c << ": Monte Carlo " << mean[c]
                      << " +- " << se[c] << ", exact " << h[c];
      }
    }
  }
  EXPECT_EQ(outside, 0);
}

TEST(Mirror, CertifiedBoundHoldsThroughMirrorsAndFiltersWithZeroViolations) {
  // The mirror room (and, for vertex tracing, a filter pane under the lamp), solved coarsely:
  // |value(T) - value(0)| <= bound(T) at every point and tolerance, and the stopping rule holds
  // for the sum of the direct and the mirrored terms.
  for (const bool with_pane : {false, true}) {
    Scene scene = mirror_room(Rgb(0.9, 0.8, 0.7));
    if (with_pane) {
      SceneBuilder b;
      b.scene() = scene;
      b.rectangle(-0.5, 1.0, -1, 1, 2.5, true,
                  b.material("pane", Rgb::Constant(0.1), Rgb::Zero(), Rgb(0.2, 0.5, 0.8)));
      scene = b.scene();
    }
    SolverSettings settings;
    settings.patch_size = 0.2;
    settings.refine_passes = 1;
    settings.unshot_fraction = 1e-2;
    const std::vector<EmittingFace> faces =
        faces_from_solution(scene, solve(RayCaster(scene), settings));
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> ux(-2.9, 1.45), uy(-2.9, 2.9);
    std::vector<Vec3> points;
    for (int i = 0; i < 40; ++i) points.push_back(Vec3(ux(rng), uy(rng), 0));
    for (const Method method : kExact) {
      if (with_pane && method == Method::hemisphere) continue;  // it refuses filters
      const LocalPass pass(scene, faces, method);
      std::vector<Rgb> exact;
      int mirrored = 0;
      for (const Vec3& x : points) {
        const LocalPassResult r = pass.gather(x, Vec3::UnitZ(), 0);
        exact.push_back(r.irradiance);
        mirrored += r.mirrored > 0;
      }
      EXPECT_GT(mirrored, 20);
      for (const double tolerance : {0.01, 0.05, 0.2, 0.5}) {
        int violations = 0, stopped_late = 0;
        for (size_t i = 0; i < points.size(); ++i) {
          const LocalPassResult r = pass.gather(points[i], Vec3::UnitZ(), tolerance);
          const Rgb error = (r.irradiance - exact[i]).cwiseAbs();
          const Rgb slack = Rgb::Constant(1e-12) + 1e-12 * exact[i];
          if (((error - r.bound).array() > slack.array()).any() && ++violations <= 3) {
            ADD_FAILURE() << method_name(method) << " T=" << tolerance << " at "
                          << points[i].transpose() << ": error " << error.transpose() << " bound "
                          << r.bound.transpose();
          }
          if (r.bound.maxCoeff() > tolerance * r.irradiance.maxCoeff() * (1 + 1e-12) + 1e-15)
            ++stopped_late;
        }
        EXPECT_EQ(violations, 0) << method_name(method) << " tolerance " << tolerance;
        EXPECT_EQ(stopped_late, 0) << method_name(method) << " tolerance " << tolerance;
      }
    }
  }
}

}  // namespace
}  // namespace rad
