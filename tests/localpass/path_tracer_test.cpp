// The path tracer of the scene itself (the reference): against the furnace, the furnace with a
// mirror face, Howell through a filter, and the exact gather off a mirror, each within 4
// standard errors at a fixed seed.
#include "reference/path_tracer.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "localpass/local_pass.h"
#include "scene/polygon_faces.h"
#include "scene/scene_loader.h"
#include "tests/closed_forms.h"
#include "tests/path_trace_checks.h"
#include "tests/scene_builder.h"

namespace rad {
namespace {

using test::SceneBuilder;

using test::within;

TEST(PathTracer, FurnaceIsEOverOneMinusRho) {
  // Closed cube, every face E = 1, rho = 0.5: H = B = 2 everywhere, by every bounce sampled.
  const Scene cube =
      load_scene(std::filesystem::path(RAD_SOURCE_DIR) / "data/closed-cube/scene.json");
  const PathTracer tracer(cube);
  const Vec3 points[] = {{0.5, 0.5, 0}, {0.01, 0.3, 0}, {0.99, 0.99, 0}};
  for (size_t i = 0; i < 3; ++i) {
    const PathTraceEstimate e = tracer.irradiance(points[i], Vec3::UnitZ(), 20000, i);
    EXPECT_TRUE(within(e, Rgb::Constant(2), 0.01)) << points[i].transpose();
  }
  // Seeded: the same seed, the same estimate; another seed, another.
  EXPECT_EQ(tracer.irradiance(points[0], Vec3::UnitZ(), 10, 3).mean,
            tracer.irradiance(points[0], Vec3::UnitZ(), 10, 3).mean);
  EXPECT_NE(tracer.irradiance(points[0], Vec3::UnitZ(), 10, 3).mean,
            tracer.irradiance(points[0], Vec3::UnitZ(), 10, 4).mean);
}

TEST(PathTracer, FurnaceWithAPerfectMirrorFaceIsStillTwo) {
  // The diffuse faces E = 1, rho = 0.5; the face x = 1 a perfect black mirror: it shows the
  // room, which is 2 everywhere, so H = 2 on the diffuse faces.
  SceneBuilder b;
  const int furnace = b.material("furnace", Rgb::Constant(0.5), Rgb::Ones());
  const int mirror = b.material("mirror", Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Ones());
  b.rectangle(0, 1, 0, 1, 0, false, furnace);
  b.rectangle(0, 1, 0, 1, 1, true, furnace);
  b.polygon({{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}, furnace);
  b.polygon({{1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}}, mirror);
  b.polygon({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, furnace);
  b.polygon({{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}}, furnace);
  const PathTracer tracer(b.scene());
  const Vec3 points[] = {{0.5, 0.5, 0}, {0.9, 0.2, 0}};
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_TRUE(
        within(tracer.irradiance(points[i], Vec3::UnitZ(), 20000, 10 + i), Rgb::Constant(2), 0.01))
        << points[i].transpose();
  }
}

TEST(PathTracer, LampBehindAFilterIsTransmittanceTimesHowell) {
  const Rgb t(0.2, 0.55, 0.9);
  SceneBuilder b;
  b.rectangle(0, 1, 0, 2, 1, true, b.material("lamp", Rgb::Zero(), Rgb::Ones()));
  b.rectangle(-1, 2, -1, 3, 0.5, true, b.material("glass", Rgb::Zero(), Rgb::Zero(), t));
  b.rectangle(-3, 3, -3, 3, 0, false, b.material("black", Rgb::Zero(), Rgb::Zero()));
  const PathTracer tracer(b.scene());
  EXPECT_TRUE(within(tracer.irradiance(Vec3::Zero(), Vec3::UnitZ(), 100000, 1),
                     test::howell_b3(1, 2, 1) * t, 0.01));
}

TEST(PathTracer, OffAMirrorItAgreesWithTheExactUnfoldedGather) {
  // A black room (nothing reflects diffusely): H is the lamp's light, directly and off the
  // mirror, which the local pass computes exactly by unfolding.
  SceneBuilder b;
  const int black = b.material("black", Rgb::Zero(), Rgb::Zero());
  b.rectangle(-3, 1.5, -3, 3, 0, false, black);
  b.rectangle(-1, 1.9, -0.5, 0.8, 3, true, b.material("lamp", Rgb::Zero(), Rgb(1, 2, 3)));
  b.rectangle(1.2, 1.8, -0.3, 0.4, 2, false, black);
  b.polygon({{2, -2, 0}, {2, -2, 2.5}, {2, 2, 2.5}, {2, 2, 0}},
            b.material("mirror", Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb(0.9, 0.6, 0.3)));
  const PathTracer tracer(b.scene());
  const LocalPass exact(b.scene(), faces_from_polygons(b.scene()), Method::vertex);
  const Vec3 points[] = {{0, 0, 0}, {1.0, -1.0, 0}, {-2, 1, 0}};
  for (size_t i = 0; i < 3; ++i) {
    const Rgb h = exact.gather(points[i], Vec3::UnitZ(), 0).irradiance;
    EXPECT_TRUE(within(tracer.irradiance(points[i], Vec3::UnitZ(), 100000, 20 + i), h, 0.02))
        << points[i].transpose();
  }
}

TEST(PathTracer, AtAWallsFootTheWallIsEdgeOnAsForTheExactGatherers) {
  // x on the bottom edge of a black wall, lamps on both sides: the wall's plane holds x, so it
  // neither shows nor hides (the gatherers' convention), and both lamps light x. (Rays started
  // in that plane used to meet the wall at once: half the light lost.)
  SceneBuilder b;
  const int black = b.material("black", Rgb::Zero(), Rgb::Zero());
  const int lamp = b.material("lamp", Rgb::Zero(), Rgb(1, 2, 3));
  b.rectangle(-2, 2, -2, 2, 0, false, black);
  b.polygon({{-1, 0, 0}, {1, 0, 0}, {1, 0, 1}, {-1, 0, 1}}, black);  // the wall, y = 0
  b.rectangle(-0.5, 0.5, 0.2, 0.8, 1.5, true, lamp);
  b.rectangle(-0.5, 0.5, -0.9, -0.3, 1.2, true, lamp);
  const PathTracer tracer(b.scene());
  const LocalPass exact(b.scene(), faces_from_polygons(b.scene()), Method::vertex);
  const Vec3 x(0.1, 0, 0);
  EXPECT_TRUE(within(tracer.irradiance(x, Vec3::UnitZ(), 100000, 30),
                     exact.gather(x, Vec3::UnitZ(), 0).irradiance, 0.02));
}

}  // namespace
}  // namespace rad
