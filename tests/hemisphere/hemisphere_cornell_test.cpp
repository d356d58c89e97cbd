// The hemisphere gatherer on the Cornell box: robustness over 100k surface points, and floor
// irradiance from the light against an exact value constructed independently.
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <random>

#include "geometry/clip.h"
#include "geometry/lambert.h"
#include "hemisphere/hemisphere_gatherer.h"
#include "scene/polygon_faces.h"
#include "scene/scene_loader.h"
#include "tests/surface_points.h"

namespace rad {
namespace {

const Scene& cornell() {
  static const Scene scene =
      load_scene(std::filesystem::path(RAD_SOURCE_DIR) / "data/cornell-box/scene.json");
  return scene;
}

TEST(HemisphereCornell, HundredThousandSurfacePointsGiveFiniteNonNegativeResults) {
  const Scene& scene = cornell();
  const HemisphereGatherer gatherer(faces_from_polygons(scene), scene.tolerance());
  // Points on surfaces, area-weighted; 10% on an edge and 5% on a vertex of their polygon.
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> areas;
  for (const Polygon& p : scene.polygons) areas.push_back(p.area);
  std::discrete_distribution<int> pick(areas.begin(), areas.end());
  struct Point {
    Vec3 x, n;
  };
  std::vector<Point> points;
  for (int i = 0; i < 100000; ++i) {
    const Polygon& p = scene.polygons[pick(rng)];
    const Vec3 x = test::random_surface_point(p, rng, 0.05, 0.10);
    points.push_back({x, p.normal});
  }
  std::atomic<int> bad{0};
  tbb::parallel_for(size_t(0), points.size(), [&](size_t i) {
    const HemisphereGather r = gatherer.gather(points[i].x, points[i].n);
    const bool ok = r.irradiance.allFinite() && r.irradiance.minCoeff() >= 0 &&
                    std::isfinite(r.covered) && r.covered >= 0 && r.covered <= 1 + 1e-12;
    if (!ok && bad.fetch_add(1) < 5) {
      ADD_FAILURE() << "x=" << points[i].x.transpose() << " n=" << points[i].n.transpose()
                    << " E=" << r.irradiance.transpose() << " covered=" << r.covered;
    }
  });
  EXPECT_EQ(bad.load(), 0);
}

// ---- the independent construction, in the light's plane y = 548.8

using Poly2 = std::vector<Vec2>;  // (x, z), counter-clockwise

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Splits a convex polygon by the line through a, b: the part left of a->b, the part right.
std::pair<Poly2, Poly2> split_by_line(const Poly2& poly, const Vec2& a, const Vec2& b) {
  Poly2 left, right;
  const Vec2 dir = b - a;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec2& p = poly[i];
    const Vec2& q = poly[(i + 1) % poly.size()];
    const double sp = cross2(dir, p - a), sq = cross2(dir, q - a);
    if (sp >= 0) left.push_back(p);
    if (sp <= 0) right.push_back(p);
    if ((sp > 0 && sq < 0) || (sp < 0 && sq > 0)) {
      const Vec2 c = p + (sp / (sp - sq)) * (q - p);
      left.push_back(c);
      right.push_back(c);
    }
  }
  return {left, right};
}

/// pieces minus the convex polygon `hole` (counter-clockwise): convex pieces again.
std::vector<Poly2> subtract(const std::vector<Poly2>& pieces, const Poly2& hole) {
  std::vector<Poly2> out;
  for (Poly2 piece : pieces) {
    for (size_t i = 0; i < hole.size() && piece.size() >= 3; ++i) {
      auto [inside, outside] = split_by_line(piece, hole[i], hole[(i + 1) % hole.size()]);
      if (outside.size() >= 3) out.push_back(outside);
      piece = inside;
    }
  }
  return out;
}

Poly2 counter_clockwise(Poly2 p) {
  double area = 0;
  for (size_t i = 0; i < p.size(); ++i) area += cross2(p[i], p[(i + 1) % p.size()]);
  if (area < 0) std::reverse(p.begin(), p.end());
  return p;
}

/// The exact direct irradiance at a floor point x from the light, built without the
/// hemisphere module: each block face (clipped above height h, below which no segment from x
/// to the light passes) projected from x onto the light's plane is a convex shadow; the light
/// rectangle minus the shadows is carved in 2D; Lambert's formula in 3D on the pieces.
/// `shadowing` counts the faces that hid some of the light.
double direct_floor_irradiance(const Scene& scene, const Vec3& x, double h, bool with_blocks,
                               int* shadowing) {
  constexpr double kLight = 548.8;
  std::vector<Poly2> visible{{{213, 227}, {343, 227}, {343, 332}, {213, 332}}};
  *shadowing = 0;
  for (size_t i = 0; with_blocks && i < scene.polygons.size(); ++i) {
    if (scene.objects[scene.polygons[i].object].name.find("block") == std::string::npos) continue;
    const auto clipped =
        clip_to_halfspace(scene.polygons[i].vertices, Vec3(0, h, 0), Vec3::UnitY());
    if (clipped.size() < 3) continue;
    Poly2 shadow;
    for (const Vec3& p : clipped) {
      const double s = kLight / p.y();  // x is on the floor (y = 0)
      shadow.emplace_back(x.x() + s * (p.x() - x.x()), x.z() + s * (p.z() - x.z()));
    }
    double before = 0;
    for (const Poly2& piece : visible) before += std::abs(signed_area_2d(piece));
    visible = subtract(visible, counter_clockwise(shadow));
    double after = 0;
    for (const Poly2& piece : visible) after += std::abs(signed_area_2d(piece));
    *shadowing += after < before * (1 - 1e-12) ? 1 : 0;
  }
  const int light = scene.objects[2].first_polygon;
  const Rgb emission = scene.materials[scene.polygons[light].material].emission;
  double ff = 0;
  for (const Poly2& piece : visible) {
    std::vector<Vec3> in3d;
    for (const Vec2& p : piece) in3d.emplace_back(p.x(), kLight, p.y());
    ff += point_polygon_form_factor(x, Vec3::UnitY(), in3d);
  }
  return ff * emission.x();
}

/// Side faces of the named block.
std::vector<const Polygon*> block_sides(const Scene& scene, const std::string& name) {
  std::vector<const Polygon*> sides;
  for (const Polygon& p : scene.polygons) {
    if (scene.objects[p.object].name == name && std::abs(p.normal.y()) < 0.5) sides.push_back(&p);
  }
  return sides;
}

/// Distance in the floor plane from x to the block's footprint boundary, and whether x is inside.
double footprint_gap(const std::vector<const Polygon*>& sides, const Vec3& x, bool* inside) {
  double gap = std::numeric_limits<double>::infinity();
  *inside = true;
  for (const Polygon* p : sides) {
    std::vector<Vec2> bottom;
    for (const Vec3& v : p->vertices) {
      if (v.y() == 0) bottom.emplace_back(v.x(), v.z());
    }
    const Vec2 q(x.x(), x.z()), a = bottom[0], b = bottom[1];
    const double t = std::clamp((q - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    gap = std::min(gap, (a + t * (b - a) - q).norm());
    *inside &= p->normal.dot(x - p->vertices[0]) < 0;  // behind every outward side face
  }
  return gap;
}

TEST(HemisphereCornell, FloorIrradianceFromTheLightMatchesTheIndependentConstruction) {
  const Scene& scene = cornell();
  // The light alone emits; every polygon occludes.
  std::vector<Rgb> exitance(scene.polygons.size(), Rgb::Zero());
  const int light = scene.objects[2].first_polygon;
  exitance[light] = scene.materials[scene.polygons[light].material].emission;
  const HemisphereGatherer gatherer(faces_from_polygons(scene, exitance), scene.tolerance());
  int unused = 0;
  const double scale = direct_floor_irradiance(scene, Vec3(278, 0, 280), 1, false, &unused);
  ASSERT_GT(scale, 0);

  // Floor points at least 20 mm outside both blocks' footprints.
  const auto short_block = block_sides(scene, "short block"),
             tall_block = block_sides(scene, "tall block");
  ASSERT_EQ(short_block.size(), 4u);
  ASSERT_EQ(tall_block.size(), 4u);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> ux(10, 546), uz(10, 549);
  int compared = 0, penumbra = 0;
  double worst = 0;
  for (int attempt = 0; compared < 30 && attempt < 10000; ++attempt) {
    const Vec3 x(ux(rng), 0, uz(rng));
    bool in_short = false, in_tall = false;
    const double gap =
        std::min(footprint_gap(short_block, x, &in_short), footprint_gap(tall_block, x, &in_tall));
    if (in_short || in_tall || gap < 20) continue;
    // Segments from x to the light rise at least 548.8 / 700 per unit of run, so none passes
    // below h within reach of a block at least `gap` away.
    const double h = 0.5 * gap * 548.8 / 700;
    int shadowing = 0;
    const double expected = direct_floor_irradiance(scene, x, h, true, &shadowing);
    const double unblocked = direct_floor_irradiance(scene, x, h, false, &unused);
    const double got = gatherer.gather(x, Vec3::UnitY()).irradiance.x();
    EXPECT_NEAR(got, expected, 1e-9 * scale)
        << "x = " << x.transpose() << " (" << shadowing << " shadowing faces)";
    worst = std::max(worst, std::abs(got - expected) / scale);
    ++compared;
    if (expected > 1e-9 * scale && expected < unblocked * (1 - 1e-9)) ++penumbra;
  }
  EXPECT_EQ(compared, 30);
  EXPECT_GE(penumbra, 5) << "the comparison must include points in the penumbra";
  std::cout << "compared " << compared << " floor points, " << penumbra
            << " in the penumbra; largest difference " << worst << " of the unblocked irradiance\n";
}

}  // namespace
}  // namespace rad
