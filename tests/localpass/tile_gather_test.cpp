// The tiles' certified interpolation (localpass/tile_gather.h): the kernel's curvature and
// gradient bounds hold against finite differences of the kernel's definition, and every pixel a
// tile interpolates keeps its certified bound against the tolerance-0 image: on the Cornell box,
// and on a room of shadow boundaries, contact edges, coplanar, tilted, tiny and huge polygons.
#include "localpass/tile_gather.h"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "radiosity/solution_faces.h"
#include "radiosity/solver.h"
#include "render/irradiance_render.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "tests/coarse_solution.h"

namespace rad {
namespace {

/// The kernel cos(theta_x) cos(theta_y) / (pi r^2) from its definition, for y in front of x's
/// horizon and x in front of y's plane (front normal `normal`).
double kernel(const Vec3& x, const Vec3& n, const Vec3& y, const Vec3& normal) {
  const Vec3 u = y - x;
  const double r = u.norm();
  return (n.dot(u) / r) * (normal.dot(-u) / r) / (std::numbers::pi * r * r);
}

TEST(KernelVariation, BoundsTheKernelsCurvatureAndGradientAlongTheTile) {
  // A square tile of side d in the plane z = 0 (n = +z; its points up to `slope` d off it) and
  // a box above it holding a plane's piece that faces it: at random x in the tile, y in the
  // box and directions w along the tile, the second difference of the kernel along w and its
  // gradient stay within the bounds. The largest ratio shows the bound is tight enough for a
  // halved bound to fail.
  std::mt19937_64 rng(47);
  std::uniform_real_distribution<double> u(0, 1), s(-1, 1);
  const Vec3 n = Vec3::UnitZ();
  int checked = 0, curvature_over = 0, gradient_over = 0;
  double largest = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const double d = std::pow(10.0, 2 * u(rng) - 1);  // 0.1 to 10
    const double slope = trial % 4 == 0 ? 1e-6 : 0;
    Eigen::AlignedBox3d region(Vec3(0, 0, -slope * d), Vec3(d, d, slope * d));
    // The box: anywhere from just beside the tile to far above it, any size.
    const Vec3 centre(20 * s(rng), 20 * s(rng), std::pow(10.0, 2 * u(rng) - 0.5));
    const Vec3 half = std::pow(10.0, 2 * u(rng) - 1.5) * Vec3(u(rng), u(rng), 0.2 * u(rng));
    const Eigen::AlignedBox3d box(centre - half, centre + half);
    if (!(box.min().z() > region.max().z())) continue;  // above every horizon
    Vec3 normal(s(rng), s(rng), -u(rng));
    normal.normalize();
    // Every x of the region in front of every y's plane (the normal through y faces x).
    bool facing = true;
    for (int a = 0; a < 8 && facing; ++a)
      for (int b = 0; b < 8 && facing; ++b) {
        facing = normal.dot(region.corner(Eigen::AlignedBox3d::CornerType(a)) -
                            box.corner(Eigen::AlignedBox3d::CornerType(b))) > 0;
      }
    if (!facing) continue;
    const KernelVariation v = kernel_variation(region, n, box, normal, 2 * slope);
    for (int sample = 0; sample < 20; ++sample) {
      const Vec3 x(d * u(rng), d * u(rng), slope * d * s(rng));
      const Vec3 y = box.min() + box.sizes().cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
      const double angle = 2 * std::numbers::pi * u(rng);
      const Vec3 w = Vec3(std::cos(angle), std::sin(angle), slope * s(rng)).normalized();
      const double r = (y - x).norm(), h = 1e-3 * r;
      const double k0 = kernel(x, n, y, normal);
      const double second =
          (kernel(x + h * w, n, y, normal) - 2 * k0 + kernel(x - h * w, n, y, normal)) / (h * h);
      Vec3 gradient;
      for (int a = 0; a < 3; ++a) {
        const Vec3 e = h * Vec3::Unit(a);
        gradient[a] = (kernel(x + e, n, y, normal) - kernel(x - e, n, y, normal)) / (2 * h);
      }
      ++checked;
      // The differences' own error: about 1e-6 of the value at this step.
      curvature_over += std::abs(second) > v.curvature * (1 + 1e-4);
      gradient_over += gradient.norm() > v.gradient * (1 + 1e-4);
      largest = std::max(largest, std::abs(second) / v.curvature);
    }
  }
  EXPECT_GT(checked, 2000);
  EXPECT_EQ(curvature_over, 0);
  EXPECT_EQ(gradient_over, 0);
  EXPECT_GT(largest, 0.6);  // halving the bound would be caught
}

/// |B - B_exact| <= bound at every pixel, where B_exact is the same camera's tolerance-0
/// image (the same rays, so the same visible points). Returns the violations; counts the
/// pixels the tiles interpolated.
int violations(const IrradianceImage& image, const IrradianceImage& exact, size_t* interpolated) {
  int over = 0;
  // Rounding: 1e-12 of the brightest pixel (a face's 1e-18 share may be dropped as nothing).
  double brightest = 0;
  for (const Rgb& p : exact.radiosity.pixels) brightest = std::max(brightest, p.maxCoeff());
  for (size_t i = 0; i < image.radiosity.pixels.size(); ++i) {
    const Rgb error = (image.certified_part(i) - exact.certified_part(i)).cwiseAbs();
    const Rgb allowed = image.bound.pixels[i] * (1 + 1e-9) + Rgb::Constant(1e-12 * brightest);
    if ((error.array() > allowed.array()).any() && ++over <= 3) {
      ADD_FAILURE() << "pixel " << i << (image.interpolated[i] ? " (interpolated)" : "") << ": "
                    << image.radiosity.pixels[i].transpose() << " +- "
                    << image.bound.pixels[i].transpose() << ", exact "
                    << exact.radiosity.pixels[i].transpose();
    }
    *interpolated += image.interpolated[i];
  }
  return over;
}

TEST(TileGather, EveryInterpolatedPixelOfTheCornellBoxKeepsItsBound) {
  const test::SolvedScene& s = test::coarse_cornell();
  CameraSpec spec = *s.scene.camera;
  spec.width = spec.height = 32;
  const Camera camera(spec);
  const RayCaster caster(s.scene);
  LocalPassSettings tiled, plain;
  tiled.tile = 4;
  tiled.tile_when_it_pays = false;  // every cell that can: the bound under test everywhere
  plain.tile = 0;
  const LocalPass pass(s.scene, s.faces, Method::hemisphere, tiled);
  const LocalPass plain_pass(s.scene, s.faces, Method::hemisphere, plain);
  const IrradianceImage exact = render_local_pass(s.scene, caster, camera, plain_pass, 0);
  // At tolerance 0 the tiles stand aside: the same image, bit for bit.
  const IrradianceImage exact_tiled = render_local_pass(s.scene, caster, camera, pass, 0);
  EXPECT_EQ(exact_tiled.radiosity.pixels, exact.radiosity.pixels);
  size_t interpolated = 0;
  for (const double tolerance : {0.02, 0.1, 0.3}) {
    const IrradianceImage image = render_local_pass(s.scene, caster, camera, pass, tolerance);
    EXPECT_EQ(violations(image, exact, &interpolated), 0) << "tolerance " << tolerance;
  }
  EXPECT_GT(interpolated, 300u);  // of 3 x 1,024 pixels: the tiles took part
}

TEST(TileGather, BoundsHoldAcrossShadowBoundariesContactsAndDegenerateFamilies) {
  // An open room lit by an area light: a blocker throws shadow and penumbra edges across the
  // floor's tiles; a wall and a tilted panel meet the floor along contact lines; a rug lies
  // coplanar on the floor (the two hide each other by index); a tiny square and a huge ground
  // polygon below the floor; the camera sees a wall nearly edge-on. Solved coarsely, rendered
  // at three tolerances against the tolerance-0 image.
  Scene scene = parse_scene(R"({
    "materials": {
      "white": {"reflectance": [0.7, 0.7, 0.7]},
      "red": {"reflectance": [0.6, 0.1, 0.1]},
      "lamp": {"reflectance": [0, 0, 0], "emission": [40, 40, 40]}
    },
    "objects": [
      {"name": "floor", "material": "white", "polygons": [[[0,0,0],[0,0,4],[4,0,4],[4,0,0]]]},
      {"name": "ground", "material": "white",
       "polygons": [[[-50,-0.01,-50],[-50,-0.01,50],[50,-0.01,50],[50,-0.01,-50]]]},
      {"name": "wall", "material": "red", "polygons": [[[0,0,4],[0,3,4],[4,3,4],[4,0,4]]]},
      {"name": "side", "material": "white", "polygons": [[[0,0,0],[0,3,0],[0,3,4],[0,0,4]]]},
      {"name": "panel", "material": "red", "polygons": [[[3,0,2.4],[3.6,1.2,2.6],[3.6,1.2,1.2],[3,0,1]]]},
      {"name": "rug", "material": "red", "polygons": [[[1,0,2.5],[1,0,3.5],[2.5,0,3.5],[2.5,0,2.5]]]},
      {"name": "blocker", "material": "white", "polygons": [[[1.2,1.5,1.2],[2.2,1.5,1.2],[2.2,1.5,2.2],[1.2,1.5,2.2]]]},
      {"name": "tiny", "material": "white", "polygons": [[[2.9,0.51,3.9],[2.91,0.51,3.9],[2.91,0.5,3.9],[2.9,0.5,3.9]]]},
      {"name": "lamp", "material": "lamp", "polygons": [[[1.4,2.9,1.4],[2.4,2.9,1.4],[2.4,2.9,2.4],[1.4,2.9,2.4]]]}
    ],
    "camera": {"eye": [3.9, 2.4, -1.5], "look_at": [1.6, 0.3, 2.4], "up": [0, 1, 0], "fov_deg": 60}
  })",
                            "tile-families.json");
  SolverSettings settings;
  settings.patch_size = 0.2;
  settings.refine_threshold = 0.2;
  settings.refine_passes = 1;
  settings.unshot_fraction = 1e-2;
  const RayCaster caster(scene);
  const std::vector<EmittingFace> faces = faces_from_solution(scene, solve(caster, settings));
  CameraSpec spec = *scene.camera;
  spec.width = spec.height = 40;
  const Camera camera(spec);
  LocalPassSettings plain, tiled;
  plain.tile = 0;
  tiled.tile = 6;
  tiled.tile_when_it_pays = false;
  for (const Method method : {Method::hemisphere, Method::vertex}) {
    const LocalPass plain_pass(scene, faces, method, plain), pass(scene, faces, method, tiled);
    const IrradianceImage exact = render_local_pass(scene, caster, camera, plain_pass, 0);
    ASSERT_GT(summarize(exact).pixels, 1500u);  // most pixels see a surface
    size_t interpolated = 0;
    for (const double tolerance : {0.03, 0.1, 0.3}) {
      const IrradianceImage image = render_local_pass(scene, caster, camera, pass, tolerance);
      EXPECT_EQ(violations(image, exact, &interpolated), 0) << "tolerance " << tolerance;
    }
    EXPECT_GT(interpolated, 700u);
  }
}

}  // namespace
}  // namespace rad
