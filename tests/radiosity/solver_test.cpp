// The solver against physics: the furnace, the energy ledger, a closed-form configuration
// factor, mesh independence, and determinism.
#include "radiosity/solver.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <iostream>

#include "radiosity/patch_mesh.h"
#include "scene/error.h"
#include "scene/polygon_validation.h"
#include "scene/scene_loader.h"
#include "tests/random_scenes.h"
#include "tests/scene_builder.h"

namespace rad {
namespace {

using test::SceneBuilder;

const std::filesystem::path kScenes = std::filesystem::path(RAD_SOURCE_DIR) / "data";

Solution solve_scene(const Scene& scene, const SolverSettings& settings) {
  const RayCaster caster(scene);
  return solve(caster, settings);
}

/// Largest relative deviation of any leaf's radiosity from `expected` (all channels).
double furnace_error(const Solution& s, double expected) {
  double worst = 0;
  for (const int e : s.leaves()) {
    worst =
        std::max(worst, (s.elements[e].radiosity.array() - expected).abs().maxCoeff() / expected);
  }
  return worst;
}

TEST(Solver, FurnaceGivesEOverOneMinusRhoAndErrorFallsWithThreshold) {
  // Closed cube, every face E = 1 and rho = 0.5: B = E / (1 - rho) = 2 everywhere.
  const Scene cube = load_scene(kScenes / "closed-cube/scene.json");
  double previous = 1;
  for (const double threshold : {1e-2, 1e-3, 1e-4}) {
    SolverSettings settings;
    settings.unshot_fraction = threshold;
    const Solution s = solve_scene(cube, settings);
    ASSERT_TRUE(s.stats.converged);
    const double error = furnace_error(s, 2.0);
    std::cout << "furnace: unshot threshold " << threshold << ": max relative error " << error
              << ", " << s.stats.shots << " shots, " << s.stats.elements << " elements\n";
    if (threshold == SolverSettings{}.unshot_fraction) {
      EXPECT_LT(error, 1e-3) << "at the default threshold";
    }
    EXPECT_LT(error, previous) << "the error must fall as the threshold falls";
    previous = error;
    // Radiosity grows towards 2 and does not overshoot, but for what the far field's balance
    // moves between receivers to keep each shot's energy (radiosity/near_field.h): measured
    // 5e-6 of the value.
    for (const int e : s.leaves()) ASSERT_LE(s.elements[e].radiosity.maxCoeff(), 2.0 * (1 + 1e-4));
  }
}

void expect_energy_balance(const Solution& s, const std::string& name) {
  const SolveStats& st = s.stats;
  for (int c = 0; c < 3; ++c) {
    const double sum = st.absorbed[c] + st.escaped[c] + st.unshot[c] + st.redirected[c];
    EXPECT_NEAR(sum, st.emitted[c], 1e-6 * st.emitted[c])
        << name << " channel " << c << ": emitted " << st.emitted[c] << " absorbed "
        << st.absorbed[c] << " escaped " << st.escaped[c] << " unshot " << st.unshot[c];
  }
}

TEST(Solver, TheFloorUnderABlockIsBuriedAndTheLightAroundItKept) {
  // A lamp over a floor with a block standing on it. The floor is cut along the block's foot
  // (radiosity/contact_cuts.h): what lies under the block is buried, receives nothing and sends
  // nothing; the light of the live floor around it is shot undiluted; the ledger holds.
  SceneBuilder b;
  const int white = b.material("white", Rgb::Constant(0.5), Rgb::Zero());
  b.rectangle(0, 4, 0, 4, 0, false, white);
  const std::vector<Vec3> foot{{1.3, 1.1, 0}, {2.5, 1.5, 0}, {2.1, 2.7, 0}, {0.9, 2.3, 0}};
  for (size_t i = 0; i < 4; ++i) {
    const Vec3& a = foot[i];
    const Vec3& c = foot[(i + 1) % 4];
    b.polygon({a, c, c + Vec3(0, 0, 0.8), a + Vec3(0, 0, 0.8)}, white);
  }
  b.polygon({foot[0] + Vec3(0, 0, 0.8), foot[1] + Vec3(0, 0, 0.8), foot[2] + Vec3(0, 0, 0.8),
             foot[3] + Vec3(0, 0, 0.8)},
            white);
  b.rectangle(1.5, 2.5, 1.5, 2.5, 3, true, b.material("lamp", Rgb::Zero(), Rgb::Constant(10)));
  const Solution s = solve_scene(b.scene(), SolverSettings{});
  expect_energy_balance(s, "block on a floor");
  EXPECT_NEAR(s.stats.emitted[0], 10.0, 1e-9);  // the lamp is not buried
  const auto inside = [&](const Vec3& p, double margin) {
    for (size_t i = 0; i < 4; ++i) {
      const Vec3 e = foot[(i + 1) % 4] - foot[i];
      if (e.cross(p - foot[i]).z() / e.norm() <= margin) return false;
    }
    return true;
  };
  int buried = 0, lit = 0;
  for (const int e : s.leaves()) {
    const Element& el = s.elements[e];
    if (el.polygon != 0) continue;
    if (inside(el.centroid, 1e-9)) {
      ++buried;
      EXPECT_EQ(el.irradiance, Rgb::Zero()) << "element " << e;
      EXPECT_EQ(el.radiosity, Rgb::Zero()) << "element " << e;
      for (const Vec3& c : el.corners) EXPECT_TRUE(inside(c, -1e-9)) << "straddles the foot";
    } else {
      lit += el.irradiance.maxCoeff() > 0;
    }
  }
  EXPECT_GT(buried, 0);
  EXPECT_GT(lit, 100);
}

TEST(Solver, ConservesEnergyOnThreeScenes) {
  for (const char* name : {"closed-cube", "light-over-floor", "cornell-box"}) {
    const Scene scene = load_scene(kScenes / name / "scene.json");
    SolverSettings settings;
    settings.patch_size = 0.15;  // coarse: the ledger does not depend on resolution
    const Solution s = solve_scene(scene, settings);
    expect_energy_balance(s, name);
    if (std::string(name) == "closed-cube") {
      // Closed: nothing escapes but the reciprocity error of point-sampled receivers.
      EXPECT_LT(std::abs(s.stats.escaped.sum()), 1e-2 * s.stats.emitted.sum())
          << s.stats.escaped.transpose();
    } else {
      EXPECT_GT(s.stats.escaped.minCoeff(), 0) << name << " is open: light leaves it";
      EXPECT_GT(s.stats.refined, 0)
          << name << ": the ledger must hold through adaptive refinement too";
    }
  }
}

/// Two directly opposed unit squares at distance 1; the top one emits M = 1; both black.
Scene opposed_squares() {
  Scene scene;
  scene.materials.push_back(Material{"black", Rgb::Zero(), Rgb::Zero()});
  scene.materials.push_back(Material{"lamp", Rgb::Zero(), Rgb::Ones()});
  std::vector<std::string> w;
  auto add = [&](std::vector<Vec3> v, int material, int object) {
    for (Polygon& p : make_polygons(std::move(v), "square", material, object, 0, w))
      scene.polygons.push_back(p);
    scene.objects.push_back(SceneObject{"", "", material, object, 1});
  };
  add({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, 0, 0);  // receiver, facing +z
  add({{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}}, 1, 1);  // emitter, facing -z
  return scene;
}

TEST(Solver, MatchesHowellC11ForOpposedSquares) {
  const double howell_c11 = 0.199824895698387;  // docs/formfactors.md
  const Scene scene = opposed_squares();
  for (const double patch_size : {SolverSettings{}.patch_size, SolverSettings{}.patch_size / 2}) {
    SolverSettings settings;
    settings.patch_size = patch_size;
    const Solution s = solve_scene(scene, settings);
    // Only the black receiver absorbs (the emitter receives nothing back from a black
    // receiver): absorbed power = M * A * F with M = A = 1.
    const double received = s.stats.absorbed.x();
    const double error = std::abs(received - howell_c11) / howell_c11;
    std::cout << "C-11: patch size " << patch_size << ": received " << received
              << ", relative error " << error << "\n";
    EXPECT_LT(error, patch_size == SolverSettings{}.patch_size ? 1e-2 : 1e-3);
    EXPECT_NEAR(s.stats.escaped.x(), 1 - howell_c11, 1e-2) << "the rest leaves the scene";
  }
}

/// Gouraud-interpolated radiosity at a point of polygon `polygon`.
Rgb interpolated(const Solution& s, const ElementMesh& mesh, const std::vector<Rgb>& vertex_values,
                 const Scene& scene, int polygon, const Vec3& x) {
  const Vec3& n = scene.polygons[polygon].normal;
  const PlaneFrame frame(x, n);
  for (int f = 0; f < mesh.face_count(); ++f) {
    if (s.elements[mesh.element(f)].polygon != polygon) continue;
    const auto points = mesh.face_points(f);
    std::vector<Vec2> flat;
    for (const Vec3& p : points) flat.push_back(frame.to_2d(p));
    if (!contains_2d(flat, Vec2::Zero())) continue;
    std::vector<Rgb> values;
    for (const int v : mesh.face_vertices(f)) values.push_back(vertex_values[v]);
    return interpolate_mean_value(points, values, n, x);
  }
  ADD_FAILURE() << "no element of polygon " << polygon << " contains " << x.transpose();
  return Rgb::Zero();
}

TEST(Solver, CornellBoxIsMeshIndependentAtTwentyPoints) {
  const Scene scene = load_scene(kScenes / "cornell-box/scene.json");
  // 4 points per room surface at fractions 0.15 and 0.85 of its extent (none under a block).
  struct Wall {
    int polygon;
    Vec3 origin, u, v;
  };
  const Wall walls[] = {
      {0, {0, 0, 0}, {552, 0, 0}, {0, 0, 559.2}},        // floor
      {1, {0, 548.8, 0}, {556, 0, 0}, {0, 0, 227}},      // ceiling, front piece
      {6, {0, 0, 559.2}, {549.6, 0, 0}, {0, 548.8, 0}},  // back wall
      {7, {0, 0, 0}, {0, 0, 559.2}, {0, 548.8, 0}},      // right (green) wall
      {8, {553, 0, 0}, {0, 0, 559.2}, {0, 548.8, 0}},    // left (red) wall, first triangle region
  };
  std::vector<std::pair<int, Vec3>> points;
  for (const Wall& w : walls) {
    for (double a : {0.15, 0.85}) {
      for (double b : {0.15, 0.85}) points.emplace_back(w.polygon, w.origin + a * w.u + b * w.v);
    }
  }
  // Points on the twisted left wall: project onto whichever of its two triangles holds them.
  std::vector<Rgb> values[2];
  for (int run = 0; run < 2; ++run) {
    SolverSettings settings;
    settings.element_levels =
        SolverSettings{}.element_levels + run;  // refine the initial mesh once
    const Solution s = solve_scene(scene, settings);
    const ElementMesh mesh(s, scene.tolerance().pad);
    std::vector<Rgb> rho;
    for (int f = 0; f < mesh.face_count(); ++f) {
      rho.push_back(scene.materials[scene.polygons[s.elements[mesh.element(f)].polygon].material]
                        .reflectance);
    }
    const auto vertex_values = mesh.vertex_radiosity(s, rho, false);
    for (auto [polygon, x] : points) {
      if (polygon == 8) {
        // The red wall is split in two triangles (polygons 8 and 9); snap x onto its plane.
        const Polygon& p = scene.polygons[8];
        const Vec3 on = x - p.normal.dot(x - p.vertices[0]) * p.normal;
        const PlaneFrame f(p.vertices[0], p.normal);
        std::vector<Vec2> flat;
        for (const Vec3& v : p.vertices) flat.push_back(f.to_2d(v));
        if (!contains_2d(flat, f.to_2d(on))) {
          polygon = 9;
          const Polygon& q = scene.polygons[9];
          x = x - q.normal.dot(x - q.vertices[0]) * q.normal;
        } else {
          x = on;
        }
      }
      values[run].push_back(interpolated(s, mesh, vertex_values, scene, polygon, x));
    }
  }
  // Two limits: on the mean square change over the points (the mesh as a whole), and on the
  // largest (no point far off). Measured over seeds 1-3 with 16 visibility samples: RMS 0.8% to
  // 1.2%, largest 1.7% to 3.9% (point 10, on the back wall beside the tall block's shadow: 2.7%
  // with 64 samples, so partly visibility noise, partly the mesh). Before the solver's random
  // streams were hashed (radiosity/random_stream.h), seed 1 gave 1.9% at most, under the 2% this
  // test then asked; the other streams show that margin was luck.
  double sum_squares = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const double change =
        (values[1][i] - values[0][i]).cwiseAbs().maxCoeff() / values[0][i].maxCoeff();
    sum_squares += change * change;
    EXPECT_LT(change, 0.05) << "point " << i << " " << points[i].second.transpose() << ": "
                            << values[0][i].transpose() << " -> " << values[1][i].transpose();
  }
  EXPECT_LT(std::sqrt(sum_squares / static_cast<double>(points.size())), 0.015);
}

TEST(Solver, ShaftCullingSkipsRaysWhereNothingIsBetween) {
  // Random polygons (convex, concave, interpenetrating) over a floor: the culling took part in
  // every scene and left pairs with something between them to the rays. Its soundness is
  // shadow_culling_test.cpp's. The rays it skips could only misfire (a grazing ray hitting its
  // own receiver or shooter within float rounding), so the energy budget is the same to 1%.
  int traced = 0;
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    test::RandomSceneMaker maker(seed);
    const Scene scene = maker.random_scene().scene;
    SolverSettings settings;
    settings.patch_size = 0.1;
    settings.refine_threshold = 0;
    const Solution with = solve_scene(scene, settings);
    settings.shaft_culling = false;
    const Solution without = solve_scene(scene, settings);
    EXPECT_GT(with.stats.unhidden_pairs, 0) << "seed " << seed;
    traced += with.stats.unhidden_pairs < with.stats.visibility_pairs;
    EXPECT_EQ(without.stats.unhidden_pairs, 0);
    EXPECT_EQ(with.stats.visibility_pairs, without.stats.visibility_pairs);
    EXPECT_NEAR(with.stats.absorbed.sum(), without.stats.absorbed.sum(),
                1e-2 * without.stats.absorbed.sum())
        << "seed " << seed;
  }
  EXPECT_GE(traced, 3) << "scenes where some pairs still needed rays";
}

TEST(Solver, APartlyBuriedPatchOfOneElementIsShotAsItsLiveDensity) {
  // The furnace (E = 1, rho = 0.5 everywhere) with 25 blocks standing on its floor: more contact
  // lines than the floor is cut along (64), so its patches are partly buried. At one element
  // per patch, a patch is its own only piece: gathered "in pieces" near it, its light went out
  // as its leaf's radiosity over the whole patch, of which the blocks' shadow rays saw only the
  // live part, and the rest was lost. Measured, the closed room's escaped light: 6.70% of the
  // emitted that way, 5.85% sent as the density over its live area (the far path). The rest is
  // the point-sampled receivers' reciprocity error where a centroid is buried and its patch is
  // not; the bound below sits between the two, so the near path for such patches fails it.
  test::SceneBuilder b;
  b.scene() = load_scene(kScenes / "closed-cube/scene.json");
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      const Vec3 lo(0.08 + 0.18 * i, 0, 0.08 + 0.18 * j);
      b.box(lo, lo + Vec3(0.07, 0.1, 0.07), 0);
    }
  }
  SolverSettings settings;
  settings.patch_size = 0.25;
  settings.element_levels = 0;
  settings.refine_threshold = 0;
  const Solution s = solve_scene(b.scene(), settings);
  const double lost = s.stats.escaped.cwiseAbs().maxCoeff() / s.stats.emitted.maxCoeff();
  std::cout << "escaped " << 100 * lost << "% of the emitted\n";
  EXPECT_LT(lost, 0.062);
}

TEST(Solver, IsBitwiseDeterministicAcrossThreadCounts) {
  const Scene scene = load_scene(kScenes / "light-over-floor/scene.json");
  SolverSettings settings;
  settings.patch_size = 0.1;
  Solution one;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = solve_scene(scene, settings);
  }
  const Solution many = solve_scene(scene, settings);
  ASSERT_EQ(one.elements.size(), many.elements.size());
  for (size_t e = 0; e < one.elements.size(); ++e)
    ASSERT_EQ(one.elements[e].radiosity, many.elements[e].radiosity) << e;
  EXPECT_EQ(one.stats.shots, many.stats.shots);
  // A different seed changes the jitter, so penumbra values move.
  settings.seed = 2;
  const Solution other = solve_scene(scene, settings);
  bool differs = other.elements.size() != one.elements.size();
  for (size_t e = 0; !differs && e < one.elements.size(); ++e)
    differs = other.elements[e].radiosity != one.elements[e].radiosity;
  EXPECT_TRUE(differs);
}

TEST(Solver, RejectsInvalidSettings) {
  const Scene scene = load_scene(kScenes / "closed-cube/scene.json");
  const RayCaster caster(scene);
  SolverSettings s;
  s.patch_size = 0;
  EXPECT_THROW(solve(caster, s), Error);
  s = {};
  s.unshot_fraction = 1.5;
  EXPECT_THROW(solve(caster, s), Error);
}

}  // namespace
}  // namespace rad
