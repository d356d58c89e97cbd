// Refraction through polyhedra by apparent depth contraction (paper 000 §4) in the local pass:
// its exact limits, each against something that does not use specular/refraction_images.h:
// index 1 against the thin filters of 000 §2.2 (vertex tracing through the same box as two
// filters), total internal reflection, one index per channel against three grey runs, and a
// huge uniform slab against Lambert's formula without it.
#include "geometry/refraction.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "localpass/local_pass.h"
#include "scene/polygon.h"
#include "scene/polygon_faces.h"
#include "specular/refraction_images.h"
#include "tests/closed_forms.h"
#include "tests/scene_builder.h"

namespace rad {
namespace {

using test::SceneBuilder;

/// A lamp (M = 1, [0, 1]^2 at z = 3, facing down) over a box [0.2, 0.8]^2 x [1, 2] of
/// `glass`, over a grey floor (its front up, not radiating: direct light only).
Scene lamp_over_box(const Material& glass, int refraction_depth = 2) {
  SceneBuilder b;
  b.rectangle(0, 1, 0, 1, 3, true, b.material("lamp", Rgb::Zero(), Rgb::Ones()));
  b.scene().materials.push_back(glass);
  b.box({0.2, 0.2, 1}, {0.8, 0.8, 2}, static_cast<int>(b.scene().materials.size()) - 1);
  b.rectangle(-2, 3, -2, 3, 0, false, b.material("floor", Rgb::Constant(0.5), Rgb::Zero()));
  b.scene().refraction_depth = refraction_depth;
  return b.scene();
}

Material refracting(const Rgb& ior, const Rgb& transmittance = Rgb::Ones()) {
  Material m{"glass", Rgb::Zero(), Rgb::Zero()};
  m.refraction = Refraction{ior, transmittance, false, Rgb::Zero()};
  return m;
}

const Vec3 kUp = Vec3::UnitZ();
const Vec3 kFloorPoints[] = {{0.5, 0.5, 0}, {0.35, 0.6, 0}, {0.1, 0.45, 0}, {0.9, 0.05, 0}};

LocalPassResult gather(const Scene& scene, const Vec3& x) {
  const LocalPass pass(scene, faces_from_polygons(scene), Method::vertex);
  return pass.gather(x, kUp, 0);
}

TEST(Refraction, IndexOneIsTheThinFilter) {
  // At index 1 nothing moves (k = 1) and each crossing passes t: the chains in at one facet
  // and out at another sum to the straight lines through the box, which cross two of its
  // faces. The same box as filters (t at each face, 000 §2.2) gathers that exactly.
  const Rgb t(0.3, 0.6, 0.9);
  const Scene glass = lamp_over_box(refracting(Rgb::Ones(), t));
  const Scene filter = lamp_over_box(Material{"glass", Rgb::Zero(), Rgb::Zero(), t});
  int through = 0;
  for (const Vec3& x : kFloorPoints) {
    const LocalPassResult r = gather(glass, x);
    const LocalPassResult f = gather(filter, x);
    const Rgb total = r.irradiance + r.refracted;
    EXPECT_LE((total - f.irradiance).cwiseAbs().maxCoeff(), 1e-12 * f.irradiance.maxCoeff())
        << "at " << x.transpose() << ": " << r.irradiance.transpose() << " + "
        << r.refracted.transpose() << " against the filters' " << f.irradiance.transpose();
    EXPECT_EQ(r.bound, Rgb::Zero());
    if (r.refracted.maxCoeff() > 0.01 * f.irradiance.maxCoeff()) ++through;
  }
  EXPECT_GE(through, 3) << "the light through the box must be a real part of the check";
}

TEST(Refraction, EachChannelIsItsOwnGreyRun) {
  // 000 §4.3: three indices, three virtual sources; channel c equals the run with index c.
  const Rgb ior(1.4, 1.5, 1.7);
  const Scene dispersive = lamp_over_box(refracting(ior, Rgb(0.9, 0.8, 0.7)));
  for (const Vec3& x : kFloorPoints) {
    const LocalPassResult r = gather(dispersive, x);
    for (int c = 0; c < 3; ++c) {
      const LocalPassResult grey =
          gather(lamp_over_box(refracting(Rgb::Constant(ior[c]), Rgb(0.9, 0.8, 0.7))), x);
      EXPECT_NEAR(r.refracted[c], grey.refracted[c], 1e-12 * grey.refracted.maxCoeff())
          << "channel " << c << " at " << x.transpose();
      EXPECT_EQ(r.irradiance[c], grey.irradiance[c]);
    }
  }
  const int images = gather(dispersive, kFloorPoints[0]).refracted_images;
  EXPECT_GE(images, 3);
  EXPECT_EQ(images % 3, 0) << "one image per index";
}

TEST(Refraction, PastTheCriticalAngleNothingComesThrough) {
  // Seen from inside (eta = 1 / n) at cos^2 <= 1 - 1 / n^2 a facet passes nothing: x inside a
  // wide flat slab looks at the top facet's centroid far off to the side.
  SceneBuilder b;
  b.rectangle(-50, 50, -50, 50, 3, true, b.material("lamp", Rgb::Zero(), Rgb::Ones()));
  const int glass = b.material("glass", Refraction{Rgb(1.5, 1.5, 1.05), Rgb::Ones()});
  b.box({0, -10, 0}, {40, 10, 1}, glass);
  const Scene& scene = b.scene();
  const std::vector<RefractingFacet> facets = refracting_facets(scene);
  const std::vector<EmittingFace> faces = faces_from_polygons(scene);
  int top = -1;
  for (size_t i = 0; i < facets.size(); ++i) {
    if (facets[i].normal.z() > 0.5) top = static_cast<int>(i);
  }
  ASSERT_GE(top, 0);
  const RefractionChain out_through_the_top{{top}, true};
  // From (19.25, 0, 0.5) the top's centroid (20, 0, 1) is at cos^2 = 0.25 / 0.8125: past the
  // critical angle of n = 1.5 (cos^2 <= 1 - 1 / 1.5^2) but not of n = 1.05 (the blue channel).
  const std::vector<RefractedImage> images =
      refracted_images(scene, faces, facets, out_through_the_top, {19.25, 0, 0.5}, 1e-9);
  ASSERT_EQ(images.size(), 1u);
  const double cos2 = 0.25 / 0.8125;
  EXPECT_LE(cos2, 1 - 1 / (1.5 * 1.5));
  EXPECT_GT(cos2, 1 - 1 / (1.05 * 1.05));
  EXPECT_EQ(images[0].weight.head<2>(), Eigen::Vector2d::Zero()) << "red and green: TIR";
  EXPECT_GT(images[0].weight[2], 0);
  // Right under the centroid every channel comes through, n^2 brighter (radiance kept / n^2).
  const std::vector<RefractedImage> under =
      refracted_images(scene, faces, facets, out_through_the_top, {20, 0, 0.5}, 1e-9);
  ASSERT_EQ(under.size(), 2u);  // the two grey channels share one image
  EXPECT_NEAR(under[0].weight[0], 1.5 * 1.5, 1e-15);
  // A hair past the critical angle: nothing; a hair short of it: all of it (the depth ratio
  // grows without bound there, the weight does not).
  const double critical_cos = std::sqrt(1 - 1 / 2.25);
  const double dx = 0.5 * std::sqrt(1 - critical_cos * critical_cos) / critical_cos;
  for (const RefractedImage& i : refracted_images(scene, faces, facets, out_through_the_top,
                                                  {20 - dx * (1 + 1e-9), 0, 0.5}, 1e-9)) {
    EXPECT_EQ(i.weight[0], 0.0) << "past the critical angle";
  }
  const std::vector<RefractedImage> short_of = refracted_images(
      scene, faces, facets, out_through_the_top, {20 - dx * (1 - 1e-9), 0, 0.5}, 1e-9);
  ASSERT_FALSE(short_of.empty());
  EXPECT_NEAR(short_of[0].weight[0], 2.25, 1e-15);
}

TEST(Refraction, AHugeUniformSlabChangesNothing) {
  // An infinite uniform source seen through an infinite slab: the contraction moves the
  // source in depth only, which does not change what an infinite plane gives, and the
  // radiance factors of the two crossings cancel. Finite here (10^4 wide, 1 to 3 high), to the
  // deficit of the finite source.
  SceneBuilder b;
  const double half = 1e4;
  b.rectangle(-half, half, -half, half, 3, true, b.material("lamp", Rgb::Zero(), Rgb::Ones()));
  b.box({-half, -half, 1}, {half, half, 2}, b.material("glass", Refraction{Rgb::Constant(1.5)}));
  const Scene& scene = b.scene();
  const LocalPassResult r = gather(scene, Vec3::Zero());
  const double deficit = 1 - test::howell_rectangle(-half, half, -half, half, 3);
  EXPECT_EQ(r.irradiance, Rgb::Zero()) << "the slab hides the lamp from straight lines";
  EXPECT_NEAR(r.refracted[0], 1, 2 * deficit) << "deficit " << deficit;
  EXPECT_GT(r.refracted_images, 0);
}

TEST(Refraction, ChainsGoInAndOutOfABox) {
  // From outside: in at one face, out at another of the same box (each face lies partly
  // behind each other one: 6 x 5 = 30 ordered pairs); from inside: out at any face (6).
  const Scene scene = lamp_over_box(refracting(Rgb::Constant(1.5)));
  const std::vector<RefractingFacet> facets = refracting_facets(scene);
  ASSERT_EQ(facets.size(), 6u);
  int from_outside = 0, from_inside = 0;
  for (const RefractionChain& c : refraction_chains(facets, 2, 1e-9)) {
    (c.from_inside ? from_inside : from_outside)++;
    EXPECT_EQ(c.facets.size(), c.from_inside ? 1u : 2u);
  }
  EXPECT_EQ(from_outside, 30);
  EXPECT_EQ(from_inside, 6);
  EXPECT_TRUE(refraction_chains(facets, 0, 1e-9).empty());
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

/// A receiver at the bottom of water (index 1.33, [-half, half]^2 x [-1, 1], x at the origin in
/// it) under a huge uniform lamp (M = 1 at z = 3).
Scene under_water(double half) {
  SceneBuilder b;
  b.rectangle(-1e4, 1e4, -1e4, 1e4, 3, true, b.material("lamp", Rgb::Zero(), Rgb::Ones()));
  b.box({-half, -half, -1}, {half, half, 1}, b.material("water", Refraction{Rgb::Constant(1.33)}));
  return b.scene();
}

TEST(RefractionKnob, UnderWaterTheSkyConvergesToTheClosedForm) {
  // Inside a medium under a uniform sky H = M (the radiance n^2 L fills only the critical cone;
  // tests/reference/path_tracer_refraction_test.cpp checks the path tracer against it). The
  // paper's heuristic takes one angle for the whole surface, straight up from x, and sees the
  // whole sky n^2 brighter: n^2 M. Split until the depth ratio varies by 1%, the pieces past
  // the critical angle pass nothing and the rest converge on M.
  const Scene scene = under_water(1e3);
  const LocalPass plain(scene, faces_from_polygons(scene), Method::vertex);
  const double n2 = 1.33 * 1.33;
  EXPECT_NEAR(plain.gather(Vec3::Zero(), kUp, 0).refracted[0], n2, 0.01 * n2);
  LocalPassSettings settings;
  settings.refraction_tolerance = 0.01;
  settings.refraction_max_pieces = 4096;
  const LocalPass knob(scene, faces_from_polygons(scene), Method::vertex, settings);
  const LocalPassResult r = knob.gather(Vec3::Zero(), kUp, 0);
  EXPECT_NEAR(r.refracted[0], 1, 0.02) << r.refracted_images << " images";
}

TEST(RefractionKnob, PiecesTileTheFacetAndMeetTheTolerance) {
  // The box's facets seen from a floor point beside it, going in (no critical angle): split
  // until the depth ratio at every corner of every piece is within the tolerance of its value
  // at the piece's centroid, the pieces tiling the facet in its plane.
  const Scene scene = lamp_over_box(refracting(Rgb(1.4, 1.5, 1.6)));
  const Vec3 x = kFloorPoints[1];
  int split = 0;  // pieces added at the tight tolerance
  for (const RefractingFacet& f : refracting_facets(scene)) {
    if (!(f.height(x) > 0)) continue;
    const double area = 0.5 * newell_vector(f.outline).norm();
    const std::vector<RefractingFacet> whole =
        facet_pieces(f, x, true, std::numeric_limits<double>::infinity(), 64);
    ASSERT_EQ(whole.size(), 1u) << "an infinite tolerance keeps the facet";
    EXPECT_EQ(whole[0].outline, f.outline);
    for (const double tolerance : {0.5, 0.05}) {
      const std::vector<RefractingFacet> pieces = facet_pieces(f, x, true, tolerance, 4096);
      EXPECT_LT(pieces.size(), 4096u) << "met before the budget";
      if (tolerance < 0.1) split += static_cast<int>(pieces.size()) - 1;
      double sum = 0;
      for (const RefractingFacet& p : pieces) {
        sum += 0.5 * newell_vector(p.outline).norm();
        EXPECT_EQ(p.normal, f.normal);
        EXPECT_EQ(p.polygon, f.polygon);
        const auto ratio = [&](const Vec3& v, int c) {
          const double cos_near = std::abs((v - x).normalized().dot(f.normal));
          return *depth_ratio(cos_near, p.refraction.ior[c]);
        };
        for (const Vec3& v : p.outline) {
          EXPECT_NEAR(f.height(v), 0, 1e-9) << "off the plane";
          for (int c = 0; c < 3; ++c) {
            const double middle = ratio(p.centroid, c);
            EXPECT_LE(std::abs(ratio(v, c) - middle), tolerance * middle * (1 + 1e-12));
          }
        }
      }
      EXPECT_NEAR(sum, area, 1e-9 * area) << "the pieces tile the facet";
    }
  }
  EXPECT_GT(split, 4) << "the tight tolerance must split";
}

/// Glass of index 1.5 between z = 1 and 1.5, the lamp of lamp_over_box at z = 3: the
/// irradiance at floor point (x0, y0) by quadrature of the slab's exact optics. A ray leaving
/// the floor at angle theta keeps it above the slab (parallel faces) and is offset sideways
/// inside, reaching the lamp's plane at r(theta) = 1 tan(theta) + 0.5 tan(theta_2) + 1.5
/// tan(theta), sin(theta_2) = sin(theta) / 1.5; the radiance factors of the two crossings
/// cancel, so H = (1 / pi) integral over the lamp of cos(theta) sin(theta) / (r r'(theta)) dA
/// (the solid angle dw = sin(theta) dtheta dphi against dA = r dr dphi), by composite
/// Gauss-Legendre, theta found from r by bisection. No apparent depths: independent of
/// specular/refraction_images.h.
double slab_quadrature(double x0, double y0) {
  const auto reach = [](double theta) {
    const double inside = std::asin(std::sin(theta) / 1.5);
    return 2.5 * std::tan(theta) + 0.5 * std::tan(inside);
  };
  const auto reach_slope = [](double theta) {
    const double s = std::sin(theta) / 1.5;
    const double c = std::cos(theta);
    return 2.5 / (c * c) + 0.5 * (c / 1.5) / std::pow(1 - s * s, 1.5);
  };
  const double nodes[5] = {-0.9061798459386640, -0.5384693101056831, 0, 0.5384693101056831,
                           0.9061798459386640};
  const double weights[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                             0.4786286704993665, 0.2369268850561891};
  const int cells = 48;
  double sum = 0;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j)
      for (int a = 0; a < 5; ++a)
        for (int b = 0; b < 5; ++b) {
          const double u = (i + 0.5 + 0.5 * nodes[a]) / cells;
          const double v = (j + 0.5 + 0.5 * nodes[b]) / cells;
          const double r = std::hypot(u - x0, v - y0);
          double lo = 0, hi = M_PI / 2;
          for (int step = 0; step < 100; ++step) {
            const double mid = 0.5 * (lo + hi);
            (reach(mid) < r ? lo : hi) = mid;
          }
          const double theta = 0.5 * (lo + hi);
          const double w = weights[a] * weights[b] / (4.0 * cells * cells);
          sum += w * std::cos(theta) * std::sin(theta) / (r * reach_slope(theta));
        }
  return sum / M_PI;
}

TEST(RefractionKnob, ConvergesThroughASlabsTwoFacesToItsQuadrature) {
  // A wide pane (40 x 40, index 1.5, clear, no Fresnel) between the lamp and the floor: light
  // goes in at the bottom face and out at the top. The paper's centroid path runs from the
  // bottom's centroid to the top's, where no light goes: 20-30% off away from the lamp's foot.
  // Along the traced ray the two contractions undo each other's angle, and splitting the
  // bottom face converges on the quadrature.
  SceneBuilder b;
  b.rectangle(0, 1, 0, 1, 3, true, b.material("lamp", Rgb::Zero(), Rgb::Ones()));
  b.box({-19.5, -19.5, 1}, {20.5, 20.5, 1.5}, b.material("glass", Refraction{Rgb::Constant(1.5)}));
  b.scene().refraction_depth = 2;
  const Scene& scene = b.scene();
  const LocalPass paper(scene, faces_from_polygons(scene), Method::vertex);
  LocalPassSettings settings;
  settings.refraction_max_pieces = 4096;
  settings.refraction_tolerance = 0.1;
  const LocalPass coarse(scene, faces_from_polygons(scene), Method::vertex, settings);
  settings.refraction_tolerance = 0.02;
  const LocalPass fine(scene, faces_from_polygons(scene), Method::vertex, settings);
  for (const Vec3& x : {Vec3(1.5, 0.5, 0), Vec3(3.5, 1.5, 0)}) {
    const double reference = slab_quadrature(x.x(), x.y());
    const auto error = [&](const LocalPass& pass) {
      const LocalPassResult r = pass.gather(x, kUp, 0);
      EXPECT_EQ(r.irradiance, Rgb::Zero()) << "the slab hides the lamp from straight lines";
      return std::abs(r.refracted[0] - reference) / reference;
    };
    EXPECT_GT(error(paper), 0.15) << "the paper's method at " << x.transpose();
    EXPECT_LT(error(coarse), 0.01) << "tolerance 0.1 at " << x.transpose();
    EXPECT_LT(error(fine), 0.004) << "tolerance 0.02 at " << x.transpose();
  }
}

TEST(RefractionKnob, CullingChangesNothing) {
  // A path whose later pieces' images lie outside the earlier ones' passes no line from x
  // (may_pass): skipping it changes nothing.
  const Scene scene = lamp_over_box(refracting(Rgb(1.45, 1.5, 1.6), Rgb(0.9, 0.8, 0.7)));
  LocalPassSettings settings;
  settings.refraction_tolerance = 0.2;
  const LocalPass culled(scene, faces_from_polygons(scene), Method::vertex, settings);
  settings.refraction_culling = false;
  const LocalPass every(scene, faces_from_polygons(scene), Method::vertex, settings);
  int fewer = 0;
  for (const Vec3& x : kFloorPoints) {
    const LocalPassResult a = culled.gather(x, kUp, 0), b = every.gather(x, kUp, 0);
    EXPECT_LE((a.refracted - b.refracted).cwiseAbs().maxCoeff(), 1e-12 * b.refracted.maxCoeff())
        << "at " << x.transpose() << ": " << a.refracted.transpose() << " against "
        << b.refracted.transpose();
    if (a.refracted_images < b.refracted_images) ++fewer;
  }
  EXPECT_GE(fewer, 2) << "the culling must take part";
}

/// An icosahedron of `material` (radius 0.5, centred at (0.5, 0.5, 1.5)), fronts out, under
/// the lamp of lamp_over_box.
Scene lamp_over_icosahedron(const Material& glass, int refraction_depth) {
  SceneBuilder b;
  b.rectangle(0, 1, 0, 1, 3, true, b.material("lamp", Rgb::Zero(), Rgb::Ones()));
  b.scene().materials.push_back(glass);
  const int m = static_cast<int>(b.scene().materials.size()) - 1;
  const double g = (1 + std::sqrt(5.0)) / 2, s = 0.5 / std::sqrt(1 + g * g);
  const Vec3 c(0.5, 0.5, 1.5);
  const std::vector<Vec3> v{{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                            {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                            {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                            {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                            {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                            {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  const int first = static_cast<int>(b.scene().polygons.size());
  for (const auto& f : faces) b.polygon({c + s * v[f[0]], c + s * v[f[1]], c + s * v[f[2]]}, m);
  for (int p = first; p < static_cast<int>(b.scene().polygons.size()); ++p)
    b.scene().polygons[p].object = b.scene().polygons[first].object;
  b.rectangle(-2, 3, -2, 3, 0, false, b.material("floor", Rgb::Constant(0.5), Rgb::Zero()));
  b.scene().refraction_depth = refraction_depth;
  return b.scene();
}

TEST(RefractionDegenerate, AnIcosahedronOfIndexOneIsItsFilter) {
  // Chains of depth 2 through 20 faces (each line crosses two of a convex solid), against the
  // same solid as thin filters; at depth 4, paths in and out and in again exist but a convex
  // solid lets no line do so: the same values.
  const Rgb t(0.5, 0.7, 0.9);
  const Scene filter = lamp_over_icosahedron(Material{"glass", Rgb::Zero(), Rgb::Zero(), t}, 2);
  for (const int depth : {2, 4}) {
    const Scene glass = lamp_over_icosahedron(refracting(Rgb::Ones(), t), depth);
    EXPECT_GT(refraction_chains(refracting_facets(glass), depth, 1e-9).size(), 300u);
    for (const Vec3& x : kFloorPoints) {
      const LocalPassResult r = gather(glass, x), f = gather(filter, x);
      EXPECT_LE((r.irradiance + r.refracted - f.irradiance).cwiseAbs().maxCoeff(),
                1e-11 * f.irradiance.maxCoeff())
          << "depth " << depth << " at " << x.transpose() << ": " << r.refracted.transpose()
          << " through, against the filters' " << f.irradiance.transpose();
    }
  }
}

TEST(RefractionDegenerate, ReceiversOnFacetsEdgesAndPlanesGiveFiniteLight) {
  // The receiver on a facet (the floor under a block resting on it), on an edge, at a vertex,
  // in a facet's plane outside it (edge-on: cos = 0 at that facet), inside: finite, never
  // negative beyond rounding, with the knob off and on.
  SceneBuilder b;
  b.rectangle(0, 1, 0, 1, 3, true, b.material("lamp", Rgb::Zero(), Rgb::Ones()));
  b.box({0.2, 0.2, 0}, {0.8, 0.8, 1}, b.material("glass", Refraction{Rgb(1.4, 1.5, 1.6)}));
  b.rectangle(-2, 3, -2, 3, 0, false, b.material("floor", Rgb::Constant(0.5), Rgb::Zero()));
  const Scene& scene = b.scene();
  const std::vector<std::pair<Vec3, Vec3>> receivers{{{0.5, 0.5, 0}, kUp},
                                                     {{0.2, 0.5, 0}, kUp},
                                                     {{0.2, 0.2, 0}, kUp},
                                                     {{0.1, 0.5, 0}, kUp},
                                                     {{0.5, 0.5, 0.5}, kUp},
                                                     {{0.8, 0.5, 0.5}, Vec3::UnitX()},
                                                     {{1.5, 0.5, 0.5}, -Vec3::UnitX()},
                                                     {{0.5, 0.5, 1}, kUp},
                                                     {{0.9, 0.9, 1}, kUp}};
  for (const double knob : {std::numeric_limits<double>::infinity(), 0.2}) {
    LocalPassSettings settings;
    settings.refraction_tolerance = knob;
    const LocalPass pass(scene, faces_from_polygons(scene), Method::vertex, settings);
    int lit = 0;
    for (const auto& [x, n] : receivers) {
      const LocalPassResult r = pass.gather(x, n, 0);
      EXPECT_TRUE(r.refracted.allFinite() && r.irradiance.allFinite()) << x.transpose();
      EXPECT_GE(r.refracted.minCoeff(), -1e-12) << x.transpose();
      if (r.refracted.maxCoeff() > 0.01) ++lit;
    }
    EXPECT_GE(lit, 3) << "knob " << knob;
  }
}

}  // namespace
}  // namespace rad
