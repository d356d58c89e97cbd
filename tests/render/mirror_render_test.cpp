// Eye rays off mirrors (paper 000 §3): the Cornell box seen in a perfect mirror, from the
// camera's mirror image, is the box seen from the camera, flipped left to right.
#include <gtest/gtest.h>

#include "render/irradiance_render.h"
#include "scene/polygon_validation.h"
#include "scene/scene_loader.h"
#include "tests/coarse_solution.h"

namespace rad {
namespace {

TEST(MirrorRender, TheBoxInAMirrorIsTheBoxSeenFromTheCamerasImage) {
  // The camera looks at the open front (z = 0) from z = -800. A perfect mirror at z = -400
  // faces the box; the camera's image in it stands at z = 0 looking towards -z. Each of its eye
  // rays, reflected, is one of the camera's own (the left-right flip of the pixel grid), and
  // meets the same points, so the pixels agree. The local pass ignores the mirror here
  // (mirror depth 0 in its settings) so that the box's light is the same in both scenes.
  const test::SolvedScene& s = test::coarse_cornell();
  Scene mirrored = s.scene;
  mirrored.materials.push_back(
      Material{"mirror", Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Ones()});
  std::vector<std::string> warnings;
  for (Polygon& p :
       make_polygons({{-200, -200, -400}, {800, -200, -400}, {800, 800, -400}, {-200, 800, -400}},
                     "mirror", static_cast<int>(mirrored.materials.size()) - 1,
                     static_cast<int>(mirrored.objects.size()), 0, warnings)) {
    ASSERT_GT(p.normal.z(), 0.99) << "the mirror must face the box";
    mirrored.polygons.push_back(p);
  }
  mirrored.mirror_depth = 1;
  CameraSpec spec = *s.scene.camera;
  spec.width = spec.height = 10;
  CameraSpec image = spec;
  image.eye.z() = -800 - spec.eye.z();
  image.look_at.z() = -800 - spec.look_at.z();
  LocalPassSettings no_mirrors;
  no_mirrors.mirror_depth = 0;
  const LocalPass direct(s.scene, s.faces, Method::vertex, no_mirrors);
  const LocalPass through(mirrored, s.faces, Method::vertex, no_mirrors);
  for (const double tolerance : {0.0, 0.1}) {
    const IrradianceImage a =
        render_local_pass(s.scene, RayCaster(s.scene), Camera(spec), direct, tolerance);
    const IrradianceImage b =
        render_local_pass(mirrored, RayCaster(mirrored), Camera(image), through, tolerance);
    int lit = 0;
    for (int y = 0; y < 10; ++y) {
      for (int x = 0; x < 10; ++x) {
        const Rgb want = a.radiosity.pixels[y * 10 + (9 - x)];
        const Rgb got = b.radiosity.pixels[y * 10 + x];
        // At a tolerance the two passes may stop at different terms (the points agree only to
        // rounding): both values lie within their bounds of the exact one.
        const double slack =
            (a.bound.pixels[y * 10 + (9 - x)] + b.bound.pixels[y * 10 + x]).maxCoeff();
        EXPECT_LE((got - want).cwiseAbs().maxCoeff(), 1e-9 * want.maxCoeff() + 1e-12 + slack)
            << "pixel (" << x << ", " << y << ") at tolerance " << tolerance << ": "
            << got.transpose() << " against " << want.transpose();
        lit += want.maxCoeff() > 0;
      }
    }
    EXPECT_GT(lit, 60);
  }
}

TEST(PathTracedRender, TheFurnaceIsTwoInEveryPixel) {
  // Inside the closed cube (E = 1, rho = 0.5) every visible point has B = 2; the reference
  // renderer's pixels agree within their noise (4,000 paths: a standard error near 0.01).
  const Scene cube =
      load_scene(std::filesystem::path(RAD_SOURCE_DIR) / "data/closed-cube/scene.json");
  CameraSpec spec = *cube.camera;
  spec.width = spec.height = 8;
  // Off the cube's axis, so that no eye ray meets an edge exactly (there, as for the exact
  // gatherers, the neighbouring face is seen edge-on and only half the room shows).
  spec.eye = Vec3(0.4, 0.55, 0.05);
  const IrradianceImage image =
      render_path_traced(cube, RayCaster(cube), Camera(spec), PathTracer(cube), 4000);
  for (size_t i = 0; i < image.radiosity.pixels.size(); ++i)
    EXPECT_NEAR(image.radiosity.pixels[i].x(), 2.0, 0.06) << "pixel " << i;
  EXPECT_EQ(image.samples_per_pixel, 4000);
}

}  // namespace
}  // namespace rad
