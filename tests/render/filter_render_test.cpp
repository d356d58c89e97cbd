// Eye rays through filters (paper 000 §2.2): a tinted pane between the camera and the Cornell
// box's open front tints the image by its transmittance, bound included.
#include <gtest/gtest.h>

#include <algorithm>

#include "render/irradiance_render.h"
#include "scene/polygon_validation.h"
#include "tests/coarse_solution.h"

namespace rad {
namespace {

int seen_lit(const IrradianceImage& image) {
  return static_cast<int>(std::count_if(image.radiosity.pixels.begin(),
                                        image.radiosity.pixels.end(),
                                        [](const Rgb& p) { return p.maxCoeff() > 0; }));
}

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

TEST(FilterRender, ARoughenedPaneSeenFromItsBackShowsTheBoxAndTheLightThroughItsLobe) {
  // The same pane made a roughened one (glossy transmittance g, gloss sigma), its front facing
  // into the box, its back to the camera, and a point light in the box on the camera's axis.
  // The eye ray passes on through the pane at its lobe's centre (straight: RayCaster::follow),
  // so each pixel is g times the pixel without the pane, plus the light seen through the lobe
  // from the pane's back: on the axis, where the lobe peaks, pi g I rho(0) cos / (r^2 cos) =
  // g I / (2 sigma^2 r^2), r the distance from the pane to the light; nothing far off it.
  const test::SolvedScene& s = test::coarse_cornell();
  const Rgb g(0.2, 0.5, 0.8), intensity(3000, 2000, 1000);
  const double sigma = 0.05, pane_z = -100;
  const Vec3 light(278, 273, 200);  // on the camera's axis (eye (278, 273, -800), +z)
  Scene lit = s.scene;
  lit.lights.push_back({light, intensity});
  Scene with_pane = lit;
  Material rough{"rough pane", Rgb::Zero(), Rgb::Zero()};
  rough.gloss = sigma;
  rough.glossy_transmittance = g;
  with_pane.materials.push_back(rough);
  std::vector<std::string> warnings;
  for (Polygon& p : make_polygons(
           {{-100, -100, pane_z}, {700, -100, pane_z}, {700, 700, pane_z}, {-100, 700, pane_z}},
           "pane", static_cast<int>(with_pane.materials.size()) - 1,
           static_cast<int>(with_pane.objects.size()), 0, warnings)) {
    with_pane.polygons.push_back(p);
  }
  ASSERT_GT(with_pane.polygons.back().normal.z(), 0) << "its back to the camera";
  CameraSpec spec = *s.scene.camera;
  spec.width = spec.height = 11;  // pixel (5, 5) looks along the axis
  const Camera camera(spec);
  const LocalPass open(lit, s.faces, Method::vertex), paned(with_pane, s.faces, Method::vertex);
  // (Any tolerance: both renders gather the same points alike.)
  const IrradianceImage a = render_local_pass(lit, RayCaster(lit), camera, open, 0.1);
  const IrradianceImage b = render_local_pass(with_pane, RayCaster(with_pane), camera, paned, 0.1);
  const size_t axis = 5 * 11 + 5;
  const double r = light.z() - pane_z;
  const Rgb peak = g.cwiseProduct(intensity) / (2 * sigma * sigma * r * r);
  for (size_t i = 0; i < a.radiosity.pixels.size(); ++i) {
    const Rgb seen = g.cwiseProduct(a.radiosity.pixels[i]);
    const Rgb highlight = b.radiosity.pixels[i] - seen;
    if (i == axis) {
      // (glossy_highlight measures r from a ray offset off the pane: 1e-5 of it here)
      EXPECT_LE((highlight - peak).cwiseAbs().maxCoeff(), 1e-4 * peak.maxCoeff())
          << highlight.transpose() << " against " << peak.transpose();
      EXPECT_LE((b.glossy.pixels[i] - peak).cwiseAbs().maxCoeff(), 1e-4 * peak.maxCoeff())
          << "apart, as glossy light";
    } else if (i % 11 <= 1 || i % 11 >= 9 || i / 11 <= 1 || i / 11 >= 9) {
      // 4 pixels or more off the axis: 0.24 rad or more, about 5 sigma (the lobe under 1e-5
      // of its peak)
      EXPECT_LE(highlight.cwiseAbs().maxCoeff(), 1e-4 * peak.maxCoeff()) << "pixel " << i;
      EXPECT_GE(highlight.minCoeff(), -1e-12 * peak.maxCoeff()) << "pixel " << i;
    }
  }
  EXPECT_GT(seen_lit(a), 60);
}

}  // namespace
}  // namespace rad
