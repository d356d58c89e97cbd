// The progressive solver with plane mirrors (paper 000 §3): shooters' images in every chain
// of mirrors light the room, and in a closed room nothing escapes.
#include <gtest/gtest.h>

#include "localpass/local_pass.h"
#include "radiosity/solver.h"
#include "scene/polygon_faces.h"
#include "scene/ray_caster.h"
#include "tests/scene_builder.h"

namespace rad {
namespace {

using test::SceneBuilder;

TEST(MirrorSolver, TheFloorSeesTheLampAndItsImage) {
  // A nearly black floor (rho 0.01: what it sends round again is 1e-4 of its light), a lamp,
  // and a mirror wall so large that every floor point sees the lamp's whole image in it: each
  // floor element holds rho E (F_direct + s F_image) at its centre, which the exact local
  // pass computes independently (unfolding, not shooting images).
  SceneBuilder b;
  const double rho = 0.01;
  b.rectangle(-2, 1.5, -2, 2, 0, false, b.material("floor", Rgb::Constant(rho), Rgb::Zero()));
  b.rectangle(-0.5, 0.5, -0.5, 0.5, 2, true, b.material("lamp", Rgb::Zero(), Rgb(1, 2, 3)));
  const Rgb s(0.9, 0.6, 0.3);
  // Every segment from a floor point to the lamp's image (x in [3.5, 4.5] at z = 2) crosses
  // x = 2 at z in [0.33, 1.46] and |y| < 2.
  b.polygon({{2, -3, 0.1}, {2, -3, 2}, {2, 3, 2}, {2, 3, 0.1}},
            b.material("mirror", Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), s));
  const Scene& scene = b.scene();
  SolverSettings settings;
  settings.refine_threshold = 0;
  const Solution solution = solve(RayCaster(scene), settings);
  LocalPassSettings direct;
  const LocalPass exact(scene, faces_from_polygons(scene), Method::vertex, direct);
  LocalPassSettings no_mirrors;
  no_mirrors.mirror_depth = 0;
  const LocalPass lamp_only(scene, faces_from_polygons(scene), Method::vertex, no_mirrors);
  int compared = 0;
  for (const Element& e : solution.elements) {
    if (e.polygon != 0 || !e.is_leaf()) continue;
    const Rgb h = exact.gather(e.centroid, Vec3::UnitZ(), 0).irradiance;
    const Rgb h_lamp = lamp_only.gather(e.centroid, Vec3::UnitZ(), 0).irradiance;
    ASSERT_GT((h - h_lamp).minCoeff(), 0.01 * h_lamp.minCoeff()) << "the image must count";
    EXPECT_LE((e.radiosity - rho * h).cwiseAbs().maxCoeff(), 1e-3 * rho * h.maxCoeff())
        << "at " << e.centroid.transpose() << ": " << e.radiosity.transpose() << " against "
        << (rho * h).transpose();
    ++compared;
  }
  EXPECT_GT(compared, 10);
}

TEST(MirrorSolver, NothingEscapesAClosedRoomWithAMirror) {
  // A closed box (floor emitting, a mirror wall): the light the mirror reflects is delivered
  // by the images and absorbed somewhere, so escaped stays near 0 (the sampled shadow rays
  // and aperture tests make it noisy, not biased); with the mirror's specular part ignored
  // (depth 0) the same light would be lost to the mirror.
  SceneBuilder b;
  const int white = b.material("white", Rgb::Constant(0.5), Rgb::Zero());
  const int lamp = b.material("lamp", Rgb::Constant(0.5), Rgb::Ones());
  const int mirror =
      b.material("mirror", Rgb::Constant(0.05), Rgb::Zero(), Rgb::Zero(), Rgb::Constant(0.9));
  b.rectangle(0, 1, 0, 1, 0, false, lamp);
  b.rectangle(0, 1, 0, 1, 1, true, white);
  b.polygon({{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}, white);
  b.polygon({{1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}}, mirror);
  b.polygon({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, white);
  b.polygon({{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}}, white);
  const Solution s = solve(RayCaster(b.scene()), SolverSettings{});
  const SolveStats& st = s.stats;
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(st.absorbed[c] + st.escaped[c] + st.unshot[c] + st.redirected[c], st.emitted[c],
                1e-9 * st.emitted[c]);
    EXPECT_LT(std::abs(st.escaped[c]), 0.02 * st.emitted[c]) << "channel " << c;
  }
}

}  // namespace
}  // namespace rad
