// Point lights (issue 20) in the local pass and the path tracer, against the inverse-square
// cosine law I cos / r^2 (the closed form of a point source), its shadow cast by a square (the
// edge where it falls, by similar triangles), a filter's transmittance, and the furnace
// identity of a closed box: the area-mean irradiance is P / ((1 - rho) A) for any geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <utility>

#include "localpass/local_pass.h"
#include "localpass/point_light_visibility.h"
#include "reference/monte_carlo.h"
#include "reference/path_tracer.h"
#include "scene/point_lights.h"
#include "scene/polygon_faces.h"
#include "scene/ray_caster.h"
#include "tests/mirrored_light.h"
#include "tests/path_trace_checks.h"
#include "tests/random_scenes.h"
#include "tests/scene_builder.h"

namespace rad {
namespace {

using test::SceneBuilder;

const Rgb kIntensity(1, 2, 3);
const Vec3 kLight(0.3, -0.2, 2);

/// I cos / r^2 on the floor z = 0 (normal +z) at (x, y).
Rgb closed_form(double x, double y) {
  const Vec3 to = kLight - Vec3(x, y, 0);
  return kIntensity * (to.z() / std::pow(to.norm(), 3));
}

/// A black floor [-5, 5]^2 under the light, and optionally a square [-0.5, 0.5]^2 at z = 1
/// between (opaque, or a filter of transmittance `pane`).
Scene floor_scene(bool with_square, const Rgb& pane = Rgb::Zero()) {
  SceneBuilder b;
  const int black = b.material("black", Rgb::Zero(), Rgb::Zero());
  b.rectangle(-5, 5, -5, 5, 0, false, black);
  if (with_square) {
    const int square = b.material("square", Rgb::Zero(), Rgb::Zero(), pane);
    b.rectangle(-0.5, 0.5, -0.5, 0.5, 1, true, square);
  }
  b.scene().lights.push_back({kLight, kIntensity});
  return b.scene();
}

/// Floor points in front of the mirror of tests/mirrored_light.h: some see the light's image,
/// some do not.
constexpr std::pair<double, double> kMirrorSites[] = {{0.3, -0.2}, {1.0, 0.5}, {-2.0, 1.5},
                                                      {0.5, -4.0}, {1.4, 0.0}, {-4.0, -3.0}};

LocalPassResult gather(const Scene& scene, double x, double y, Method method = Method::vertex) {
  const LocalPass pass(scene, faces_from_polygons(scene), method);
  return pass.gather({x, y, 0}, {0, 0, 1}, 0);
}

void expect_near(const Rgb& value, const Rgb& expected, double relative, const std::string& at) {
  EXPECT_LE((value - expected).cwiseAbs().maxCoeff(), relative * expected.maxCoeff() + 1e-300)
      << at << ": " << value.transpose() << " against " << expected.transpose();
}

TEST(PointLight, LocalPassGivesTheInverseSquareCosineLawExactly) {
  const Scene scene = floor_scene(false);
  for (const Method method : {Method::vertex, Method::hemisphere}) {
    for (const auto& [x, y] : {std::pair{0.3, -0.2}, {0.0, 0.0}, {2.0, 1.5}, {-4.9, 4.9}}) {
      const LocalPassResult r = gather(scene, x, y, method);
      expect_near(r.irradiance, closed_form(x, y), 1e-12, "at " + std::to_string(x));
      EXPECT_EQ(r.bound, Rgb::Zero()) << "a point light is gathered exactly";
    }
  }
}

TEST(PointLight, ASquareCastsItsShadowWhereSimilarTrianglesPutIt) {
  // The square's edge x = 0.5 at z = 1, seen from the light at (0.3, -0.2, 2), falls on the
  // floor at x = 0.3 + (0.5 - 0.3) * 2 = 0.7; its edge y = 0.5 at y = -0.2 + 0.7 * 2 = 1.2.
  const Scene opaque = floor_scene(true);
  EXPECT_EQ(gather(opaque, 0.3, -0.2).irradiance, Rgb::Zero()) << "under the light";
  EXPECT_EQ(gather(opaque, 0.7 - 1e-6, 0).irradiance, Rgb::Zero()) << "just inside the edge";
  expect_near(gather(opaque, 0.7 + 1e-6, 0).irradiance, closed_form(0.7 + 1e-6, 0), 1e-12,
              "just outside the edge");
  EXPECT_EQ(gather(opaque, 0, 1.2 - 1e-6).irradiance, Rgb::Zero());
  expect_near(gather(opaque, 0, 1.2 + 1e-6).irradiance, closed_form(0, 1.2 + 1e-6), 1e-12,
              "past the other edge");
  // A filter passes its transmittance of it (000 §2.2), per channel.
  const Rgb pane(0.2, 0.5, 0.8);
  const Scene filter = floor_scene(true, pane);
  expect_near(gather(filter, 0.1, 0.1).irradiance, pane.cwiseProduct(closed_form(0.1, 0.1)), 1e-12,
              "through the filter");
  expect_near(gather(filter, 2, 0).irradiance, closed_form(2, 0), 1e-12, "beside it");
}

TEST(PointLight, APerfectMirrorShowsItsImageByTheImageMethod) {
  // The floor also receives I cos / r^2 from the light's image in the mirror, times its
  // specular, where the segment to the image crosses the mirror inside its outline
  // (tests/mirrored_light.h). Exact: no bound.
  const test::MirroredLight mirrored;
  ASSERT_LT(mirrored.scene.polygons.back().normal.x(), 0) << "the mirror faces the light";
  int reflected = 0, beside = 0;
  for (const Method method : {Method::vertex, Method::hemisphere}) {
    for (const auto& [x, y] : kMirrorSites) {
      const LocalPassResult r = gather(mirrored.scene, x, y, method);
      expect_near(r.irradiance, mirrored.expected(x, y), 1e-12,
                  "at " + std::to_string(x) + ", " + std::to_string(y));
      EXPECT_EQ(r.bound, Rgb::Zero()) << "the image of a point light is gathered exactly";
      (mirrored.reflected(x, y) == Rgb::Zero() ? beside : reflected)++;
    }
  }
  EXPECT_GE(reflected, 6) << "points that see the image";
  EXPECT_GE(beside, 2) << "points whose line to the image misses the mirror";
}

TEST(PointLight, ThePathTracerAndTheMonteCarloGatherSeeTheMirrorsImageToo) {
  // No cosine ray can hit a point light or its image: without the image in their next-event
  // light (scene/point_lights.h) the light the mirror sends is missing. Black floor, black
  // mirror but for its specular part: one path is the whole answer.
  const test::MirroredLight mirrored;
  const PathTracer tracer(mirrored.scene);
  const MonteCarloGatherer gatherer(mirrored.scene, faces_from_polygons(mirrored.scene));
  int reflected = 0;
  for (const auto& [x, y] : kMirrorSites) {
    const std::string at = "at " + std::to_string(x) + ", " + std::to_string(y);
    expect_near(tracer.irradiance({x, y, 0}, {0, 0, 1}, 4, 5).mean, mirrored.expected(x, y), 1e-12,
                "path traced " + at);
    expect_near(gatherer.gather({x, y, 0}, {0, 0, 1}, 4, 5), mirrored.expected(x, y), 1e-12,
                "Monte Carlo " + at);
    reflected += mirrored.reflected(x, y) != Rgb::Zero();
  }
  EXPECT_GE(reflected, 3);
}

TEST(PointLight, ChainsOfMirrorsAgreeWithTheLocalPassesUnfolding) {
  // A corner of two perpendicular mirrors and a third facing them, an opaque square and a
  // filter among them: images of images (depth 3). The rays of scene/point_lights.h and the
  // local pass's unfolded scenes (specular/unfolding.h) share no code but the mirror pieces;
  // both are exact, so they agree to rounding at every site, in light and in shadow.
  SceneBuilder b;
  b.rectangle(-3, 3, -3, 3, 0, false, b.material("floor", Rgb::Zero(), Rgb::Zero()));
  const int mirror =
      b.material("mirror", Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb(0.9, 0.6, 0.3));
  b.polygon({{2, -2, 0}, {2, -2, 2}, {2, 2, 2}, {2, 2, 0}}, mirror);  // x = 2, facing -x
  b.polygon({{-2, 2, 0}, {2, 2, 0}, {2, 2, 2}, {-2, 2, 2}}, mirror);  // y = 2, facing -y
  b.polygon({{-2.5, -1, 0}, {-2.5, 1, 0}, {-2.5, 1, 2}, {-2.5, -1, 2}}, mirror);  // facing +x
  b.rectangle(-0.3, 0.2, 0.1, 0.6, 0.8, true, b.material("block", Rgb::Zero(), Rgb::Zero()));
  b.rectangle(0.5, 1.2, -1, -0.2, 1.1, true,
              b.material("pane", Rgb::Zero(), Rgb::Zero(), Rgb(0.2, 0.5, 0.8)));
  b.scene().lights.push_back({Vec3(0.6, 0.9, 1.6), Rgb(1, 2, 3)});
  Scene& scene = b.scene();
  scene.mirror_depth = 3;
  ASSERT_LT(scene.polygons[1].normal.x(), 0);
  ASSERT_LT(scene.polygons[2].normal.y(), 0);
  ASSERT_GT(scene.polygons[3].normal.x(), 0);
  Scene dark = scene;
  dark.lights.clear();
  const std::vector<EmittingFace> faces = faces_from_polygons(scene);
  const LocalPass pass(scene, faces, Method::vertex), dark_pass(dark, faces, Method::vertex);
  const RayCaster caster(scene);
  const PointLightIrradiance lights(caster, scene.tolerance().ray_offset);
  EXPECT_GT(lights.image_count(), 6) << "images of images";
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-2.4, 1.9);
  int differs_from_straight = 0;
  for (int k = 0; k < 200; ++k) {
    const Vec3 x(u(rng), u(rng), 0), n(0, 0, 1);
    const Rgb exact = pass.gather(x, n, 0).irradiance - dark_pass.gather(x, n, 0).irradiance;
    const Rgb rays = lights(x, n);
    ASSERT_LE((rays - exact).cwiseAbs().maxCoeff(), 1e-9 * std::max(exact.maxCoeff(), 1e-3))
        << "at " << x.transpose() << ": " << rays.transpose() << " against " << exact.transpose();
    const Rgb straight = point_light_irradiance(scene, caster, x, n, scene.tolerance().ray_offset);
    differs_from_straight += (exact - straight).maxCoeff() > 1e-3 * exact.maxCoeff();
  }
  EXPECT_GT(differs_from_straight, 150) << "the mirrors must matter";
}

TEST(PointLight, NothingReachesAPointBehindOrInTheLightsPlane) {
  for (const Vec3& light : {Vec3(0, 0, -1), Vec3(3, 0, 0), Vec3(0.5, 0.5, 0)}) {
    Scene scene = floor_scene(false);
    scene.lights = {{light, kIntensity}};
    for (const auto& [x, y] : {std::pair{0.0, 0.0}, {0.5, 0.5}}) {
      const LocalPassResult r = gather(scene, x, y);
      EXPECT_EQ(r.irradiance, Rgb::Zero()) << "light at " << light.transpose();
      EXPECT_TRUE(r.irradiance.allFinite());
    }
  }
}

TEST(PointLight, OnlyTheCullingsCandidatesAreAskedAndTheyAreEnough) {
  // The local pass asks only the polygons that may hide anything from x (the culling's
  // candidates): on seeded random scenes (random polygons, some filters, interpenetrating at
  // will) with lights among them, its light equals the same test over every polygon (the
  // plain gather), and the Embree rays of the path tracer and the solver (scene/
  // point_lights.h), which share nothing with it but the closed form of the light.
  int lit = 0, shadowed = 0;
  for (uint64_t seed = 1; seed <= 60; ++seed) {
    test::RandomSceneMaker maker(seed);
    test::RandomScene random = maker.random_scene();
    Scene& scene = random.scene;
    const int pane = static_cast<int>(scene.materials.size());
    scene.materials.push_back(Material{"pane", Rgb::Zero(), Rgb::Zero(), Rgb(0.3, 0.6, 0.9)});
    for (size_t p = 1; p < scene.polygons.size(); p += 2) scene.polygons[p].material = pane;
    for (int i = 0; i < 2; ++i) {
      scene.lights.push_back(
          {Vec3(maker.uniform(-2, 2), maker.uniform(-2, 2), maker.uniform(0.2, 3)),
           Rgb(maker.uniform(0.1, 1), maker.uniform(0.1, 1), maker.uniform(0.1, 1))});
    }
    Scene dark = scene;
    dark.lights.clear();
    const std::vector<EmittingFace> faces = faces_from_polygons(scene);
    const LocalPass pass(scene, faces, Method::vertex), dark_pass(dark, faces, Method::vertex);
    const PointLightVisibility visibility(scene);
    std::vector<int> every(scene.polygons.size());
    for (size_t p = 0; p < every.size(); ++p) every[p] = static_cast<int>(p);
    const RayCaster caster(scene);
    for (const test::ProbeSite& site : random.sites) {
      const Rgb light = pass.gather(site.x, site.n, 0).irradiance -
                        dark_pass.gather(site.x, site.n, 0).irradiance;
      const Rgb plain = visibility.irradiance(site.x, site.n, every);
      const Rgb rays =
          point_light_irradiance(scene, caster, site.x, site.n, scene.tolerance().ray_offset);
      const double scale = 1e-9 * std::max(plain.maxCoeff(), 1e-3);
      ASSERT_LE((light - plain).cwiseAbs().maxCoeff(), scale) << "seed " << seed;
      EXPECT_LE((rays - plain).cwiseAbs().maxCoeff(), scale)
          << "seed " << seed << " at " << site.x.transpose();
      Rgb unoccluded = Rgb::Zero();
      for (const PointLight& l : scene.lights)
        unoccluded += l.unoccluded_irradiance(site.x, site.n);
      lit += plain.maxCoeff() > 0;
      shadowed += (plain.array() < unoccluded.array() * (1 - 1e-9)).any();
    }
  }
  EXPECT_GT(lit, 100) << "the test must see light";
  EXPECT_GT(shadowed, 30) << "and shadows, through filters and opaque polygons";
}

TEST(PointLight, PathTracerSeesItByNextEventEstimationAlone) {
  // A black scene: one path is the whole answer (no noise), and it is the closed form.
  const Scene scene = floor_scene(true, Rgb(0.2, 0.5, 0.8));
  const PathTracer tracer(scene);
  for (const auto& [x, y] : {std::pair{0.1, 0.1}, {2.0, 0.0}, {0.3, -0.2}}) {
    const PathTraceEstimate e = tracer.irradiance({x, y, 0}, {0, 0, 1}, 16, 3);
    expect_near(e.mean, gather(scene, x, y).irradiance, 1e-12, "path traced");
    // The variance sum2 / n - mean^2 cancels to sqrt(epsilon) of the mean, not to 0.
    EXPECT_LE(e.standard_error.maxCoeff(), 1e-7 * e.mean.maxCoeff()) << "but for rounding";
  }
}

TEST(PointLight, MonteCarloGatherAddsItWithoutNoise) {
  const Scene scene = floor_scene(true, Rgb(0.2, 0.5, 0.8));
  const MonteCarloGatherer gatherer(scene, faces_from_polygons(scene));
  for (const auto& [x, y] : {std::pair{0.1, 0.1}, {2.0, 0.0}})
    expect_near(gatherer.gather({x, y, 0}, {0, 0, 1}, 64, 5), gather(scene, x, y).irradiance, 1e-12,
                "Monte Carlo");
}

TEST(PointLight, PathTracerMeetsTheFurnaceIdentityOfAClosedBox) {
  // Inside a closed unit cube of reflectance rho, everything the light sends is absorbed after
  // 1 / (1 - rho) bounces on average: the area-mean of H over the walls is P / ((1 - rho) A),
  // P = 4 pi I, whatever the light's place. Points: the midpoints of a 20 x 20 grid on each
  // wall (the midpoint rule's own error measured on the direct part, whose area-mean is P / A).
  const double rho = 0.5;
  SceneBuilder b;
  const int white = b.material("white", Rgb::Constant(rho), Rgb::Zero());
  const Vec3 lo(0, 0, 0), hi(1, 1, 1);
  // The box's faces face out: a room is the same box with each face reversed.
  b.box(lo, hi, white);
  for (Polygon& p : b.scene().polygons) {
    std::reverse(p.vertices.begin(), p.vertices.end());
    p.normal = -p.normal;
  }
  const Rgb intensity(1, 0.5, 0.25);
  b.scene().lights.push_back({Vec3(0.35, 0.6, 0.45), intensity});
  const Scene& scene = b.scene();
  const PathTracer tracer(scene);
  const int grid = 20;
  const int paths = 200;
  Rgb mean = Rgb::Zero(), variance = Rgb::Zero(), direct = Rgb::Zero();
  int points = 0;
  uint64_t seed = 0;
  for (const Polygon& wall : scene.polygons) {
    const Vec3 origin = wall.vertices[0], u = wall.vertices[1] - origin,
               v = wall.vertices[3] - origin;
    for (int i = 0; i < grid; ++i) {
      for (int j = 0; j < grid; ++j) {
        const Vec3 x = origin + (i + 0.5) / grid * u + (j + 0.5) / grid * v;
        const PathTraceEstimate e = tracer.irradiance(x, wall.normal, paths, ++seed);
        mean += e.mean;
        variance += e.standard_error.cwiseProduct(e.standard_error);
        direct += scene.lights[0].unoccluded_irradiance(x, wall.normal);
        ++points;
      }
    }
  }
  mean /= points, direct /= points;
  const Rgb standard_error = variance.cwiseSqrt() / points;
  const Rgb power = scene.light_power();
  const double area = 6;
  const Rgb midpoint_error = (direct - power / area).cwiseAbs();
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(midpoint_error[c], 1e-3 * power[c] / area) << "the grid resolves the direct light";
    const double expected = power[c] / ((1 - rho) * area);
    // Slack for the midpoint rule's error on H: four times its measured error on the direct
    // part (the reflected light is smoother than the direct).
    EXPECT_NEAR(mean[c], expected, 4 * standard_error[c] + 4 * midpoint_error[c])
        << "channel " << c << ", standard error " << standard_error[c];
    EXPECT_LT(standard_error[c], 3e-3 * expected) << "the check must mean something";
  }
}

}  // namespace
}  // namespace rad
