// Eye rays through filters (paper 000 §2.2): a tinted pane between the camera and the Cornell
// box's open front tints the image by its transmittance, bound included.
#include <gtest/gtest.h>

#include "render/irradiance_render.h"
#include "scene/polygon_validation.h"
#include "tests/coarse_solution.h"

namespace rad {
namespace {

TEST(FilterRender, APaneBeforeTheBoxTintsEveryPixelByItsTransmittance) {
  // The pane (black, not emitting) lies outside the box, so no path inside the box crosses it:
  // each pixel is T times the pixel without it, the certified bound too, for the exact local
  // pass at any tolerance and for Monte Carlo (the same rays, seeded alike).
  const test::SolvedScene& s = test::coarse_cornell();
  Scene with_pane = s.scene;
  const Rgb t(0.25, 0.5, 0.75);
  with_pane.materials.push_back(Material{"pane", Rgb::Zero(), Rgb::Zero(), t});
  std::vector<std::string> warnings;
  for (Polygon& p :
       make_polygons({{-100, -100, -100}, {700, -100, -100}, {700, 700, -100}, {-100, 700, -100}},
                     "pane", static_cast<int>(with_pane.materials.size()) - 1,
                     static_cast<int>(with_pane.objects.size()), 0, warnings)) {
    with_pane.polygons.push_back(p);
  }
  CameraSpec spec = *s.scene.camera;
  spec.width = spec.height = 10;
  const Camera camera(spec);
  const LocalPass open(s.scene, s.faces, Method::vertex), paned(with_pane, s.faces, Method::vertex);
  for (const double tolerance : {0.0, 0.1}) {
    const IrradianceImage a =
        render_local_pass(s.scene, RayCaster(s.scene), camera, open, tolerance);
    const IrradianceImage b =
        render_local_pass(with_pane, RayCaster(with_pane), camera, paned, tolerance);
    int lit = 0;
    for (size_t i = 0; i < a.radiosity.pixels.size(); ++i) {
      const Rgb want = t.cwiseProduct(a.radiosity.pixels[i]);
      EXPECT_LE((b.radiosity.pixels[i] - want).cwiseAbs().maxCoeff(),
                1e-12 * want.maxCoeff() + 1e-15)
          << "pixel " << i << " at tolerance " << tolerance;
      const Rgb want_bound = t.cwiseProduct(a.bound.pixels[i]);
      EXPECT_LE((b.bound.pixels[i] - want_bound).cwiseAbs().maxCoeff(),
                1e-12 * want.maxCoeff() + 1e-15);
      lit += want.maxCoeff() > 0;
    }
    EXPECT_GT(lit, 60);
  }
  const MonteCarloGatherer mc_open(s.scene, s.faces), mc_paned(with_pane, s.faces);
  const IrradianceImage a = render_monte_carlo(s.scene, RayCaster(s.scene), camera, mc_open, 16);
  const IrradianceImage b =
      render_monte_carlo(with_pane, RayCaster(with_pane), camera, mc_paned, 16);
  for (size_t i = 0; i < a.radiosity.pixels.size(); ++i) {
    const Rgb want = t.cwiseProduct(a.radiosity.pixels[i]);
    EXPECT_LE((b.radiosity.pixels[i] - want).cwiseAbs().maxCoeff(), 1e-12 * want.maxCoeff() + 1e-15)
        << "Monte Carlo pixel " << i;
  }
}

}  // namespace
}  // namespace rad
