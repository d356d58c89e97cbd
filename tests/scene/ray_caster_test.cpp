#include "scene/ray_caster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "scene/polygon_validation.h"
#include "scene/scene_loader.h"
#include "tests/closed_forms.h"
#include "tests/scene_builder.h"

namespace rad {
namespace {

/// Reference intersection in double precision, independent of Embree and of the
/// triangulation: plane hit, then point-in-polygon in the polygon's plane.
struct BruteHit {
  int polygon = -1;
  double distance = std::numeric_limits<double>::infinity();
  double second = std::numeric_limits<double>::infinity();  ///< next-nearest other polygon
  double edge_gap = 0;  ///< distance of the hit point to its polygon's boundary
};

double distance_to_boundary(const std::vector<Vec2>& poly, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % poly.size()];
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * (b - a) - p).norm());
  }
  return best;
}

BruteHit brute_force(const Scene& scene, const Ray& ray) {
  BruteHit best;
  for (size_t i = 0; i < scene.polygons.size(); ++i) {
    const Polygon& p = scene.polygons[i];
    const double denom = p.normal.dot(ray.direction);
    if (denom == 0) continue;
    const double t = p.normal.dot(p.vertices[0] - ray.origin) / denom;
    if (!(t > 0)) continue;
    const PlaneFrame frame(p.vertices[0], p.normal);
    std::vector<Vec2> flat;
    for (const Vec3& v : p.vertices) flat.push_back(frame.to_2d(v));
    const Vec2 q = frame.to_2d(ray.origin + t * ray.direction);
    if (!contains_2d(flat, q)) continue;
    if (t < best.distance) {
      best.second = best.distance;
      best.polygon = static_cast<int>(i);
      best.distance = t;
      best.edge_gap = distance_to_boundary(flat, q);
    } else {
      best.second = std::min(best.second, t);
    }
  }
  return best;
}

/// A soup of random triangles and quads (random orientation, sizes over three decades) in a
/// unit box, with a concave polygon mixed in.
Scene random_scene(std::mt19937_64& rng, int count) {
  Scene scene;
  scene.materials.push_back(Material{"m", Rgb::Constant(0.5), Rgb::Zero()});
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g;
  std::vector<std::string> warnings;
  for (int i = 0; i < count; ++i) {
    const Vec3 centre(u(rng), u(rng), u(rng));
    const Vec3 n = Vec3(g(rng), g(rng), g(rng)).normalized();
    const PlaneFrame frame(centre, n);
    const double size = 0.3 * std::pow(10.0, -2 * u(rng));
    const int corners = 3 + i % 4;
    std::vector<Vec3> vertices;
    for (int k = 0; k < corners; ++k) {
      const double a = 2 * M_PI * k / corners;
      const double r = size * (k % 2 && corners > 4 ? 0.4 : 1.0);  // concave for 6 corners
      vertices.push_back(centre + r * (std::cos(a) * frame.u + std::sin(a) * frame.v));
    }
    for (Polygon& p : make_polygons(vertices, "random", 0, 0, i, warnings)) {
      scene.polygons.push_back(std::move(p));
    }
  }
  return scene;
}

void compare_with_brute_force(const Scene& scene, std::mt19937_64& rng, const Vec3& lo,
                              const Vec3& hi, int ray_count) {
  const RayCaster caster(scene);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g;
  const double scale = (hi - lo).norm();
  int compared = 0, ambiguous = 0, hits = 0;
  for (int i = 0; i < ray_count; ++i) {
    const Vec3 origin = lo + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(hi - lo);
    const Ray ray{origin, Vec3(g(rng), g(rng), g(rng)).normalized()};
    const BruteHit expected = brute_force(scene, ray);
    const auto hit = caster.closest_hit(ray);
    // Float traversal cannot separate hits closer than its precision (~1e-7 of the scene's
    // size, times a few): a hit within 1e-5 of its polygon's boundary, a second polygon within
    // 1e-4 relative depth, or a hit closer than 1e-5 to the origin, is ambiguous.
    const double resolution = 1e-5 * scale;
    if (expected.polygon >= 0 &&
        (expected.edge_gap < resolution || expected.distance < resolution ||
         expected.second - expected.distance < 1e-4 * expected.distance)) {
      ++ambiguous;
      continue;
    }
    ++compared;
    ASSERT_EQ(hit.has_value(), expected.polygon >= 0)
        << "ray " << i << " origin " << ray.origin.transpose() << " dir "
        << ray.direction.transpose();
    if (!hit) continue;
    ++hits;
    ASSERT_EQ(hit->polygon, expected.polygon) << "ray " << i;
    ASSERT_NEAR(hit->distance, expected.distance, 1e-4 * expected.distance) << "ray " << i;
    // The double-precision refinement puts the point on the polygon's plane.
    const Polygon& p = scene.polygons[hit->polygon];
    EXPECT_NEAR(p.normal.dot(hit->point - p.vertices[0]), 0, 1e-12 * scale) << "ray " << i;
    EXPECT_EQ(hit->front_facing, p.normal.dot(ray.direction) < 0);
    // Occlusion agrees with the closest hit on both sides of it.
    EXPECT_TRUE(caster.occluded(ray, 0, hit->distance * 1.001 + resolution)) << "ray " << i;
    EXPECT_FALSE(caster.occluded(ray, 0, hit->distance * 0.999 - resolution)) << "ray " << i;
  }
  EXPECT_LT(ambiguous, ray_count / 50) << "too many ambiguous rays to call this a test";
  EXPECT_GT(hits, ray_count / 10) << "too few hits to call this a test";
  std::cout << "compared " << compared << " rays (" << hits << " hits), " << ambiguous
            << " ambiguous rays left out\n";
}

TEST(RayCaster, MatchesBruteForceOnRandomPolygonSoup) {
  std::mt19937_64 rng(12345);
  const Scene scene = random_scene(rng, 400);
  compare_with_brute_force(scene, rng, Vec3(-0.2, -0.2, -0.2), Vec3(1.2, 1.2, 1.2), 10000);
}

TEST(RayCaster, MatchesBruteForceInsideCornellBox) {
  const Scene scene =
      load_scene(std::filesystem::path(RAD_SOURCE_DIR) / "data/cornell-box/scene.json");
  std::mt19937_64 rng(99);
  // Origins inside the box; rays leaving through the open front (z = 0) must miss.
  compare_with_brute_force(scene, rng, Vec3(10, 10, 10), Vec3(546, 538, 549), 10000);
}

TEST(RayCaster, AStreamOfSegmentsGetsTheAnswersOfOneRayAtATime) {
  // The solver's shadow rays: from a point to 16 points spread over a region, as one stream
  // (packets inside Embree); each answer must be the single query's, blocked or not.
  const Scene scene =
      load_scene(std::filesystem::path(RAD_SOURCE_DIR) / "data/cornell-box/scene.json");
  const RayCaster caster(scene);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  const auto inside = [&] { return Vec3(10 + 536 * u(rng), 10 + 528 * u(rng), 10 + 539 * u(rng)); };
  int blocked_count = 0, total = 0;
  std::vector<RayCaster::Segment> segments;
  std::vector<char> blocked;
  for (int i = 0; i < 300; ++i) {
    const Vec3 x = inside(), centre = inside();
    segments.clear();
    for (int k = 0; k < 16; ++k) {
      const Vec3 d = centre + Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5) * 100 - x;
      segments.push_back({{x, d.normalized()}, 1e-3, d.norm() * (1 - 1e-6) - 1e-3});
    }
    caster.occluded(segments, blocked);
    ASSERT_EQ(blocked.size(), segments.size());
    for (size_t k = 0; k < segments.size(); ++k) {
      const RayCaster::Segment& s = segments[k];
      EXPECT_EQ(bool(blocked[k]), caster.occluded(s.ray, s.t_min, s.t_max)) << i << " " << k;
      blocked_count += blocked[k];
      ++total;
    }
  }
  // Both answers occur often enough for the comparison to mean something.
  EXPECT_GT(blocked_count, total / 20);
  EXPECT_LT(blocked_count, total - total / 20);
  segments.clear();
  caster.occluded(segments, blocked);
  EXPECT_TRUE(blocked.empty());
}

TEST(RayCaster, RespectsDistanceInterval) {
  Scene scene;
  scene.materials.push_back(Material{"m", Rgb::Constant(0.5), Rgb::Zero()});
  std::vector<std::string> warnings;
  for (double z : {1.0, 2.0}) {
    // Facing -z (towards the origin): clockwise seen from +z.
    for (Polygon& p :
         make_polygons({{-1, -1, z}, {-1, 1, z}, {1, 1, z}, {1, -1, z}}, "q", 0, 0, 0, warnings)) {
      scene.polygons.push_back(p);
    }
  }
  const RayCaster caster(scene);
  const Ray ray{{0.1, 0.2, 0}, {0, 0, 1}};
  auto hit = caster.closest_hit(ray);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->polygon, 0);
  EXPECT_DOUBLE_EQ(hit->distance, 1.0);
  EXPECT_TRUE(hit->front_facing);
  hit = caster.closest_hit(ray, 1.5);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->polygon, 1);
  EXPECT_FALSE(caster.closest_hit(ray, 0, 0.5));
  // Seen from behind, a polygon still blocks (opaque from both sides).
  const Ray back{{0.1, 0.2, 3}, {0, 0, -1}};
  hit = caster.closest_hit(back);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->polygon, 1);
  EXPECT_FALSE(hit->front_facing);
  EXPECT_TRUE(caster.occluded(back, 0, 10));
  EXPECT_FALSE(caster.occluded(Ray{{5, 5, 0}, {0, 0, 1}}, 0, 10));
}

TEST(RayCaster, FollowsARayThroughAGlassSlabBySnellsLaw) {
  // A slab of index 1.5 from z = 1 to 2 over the origin, a ceiling at z = 3: a ray at angle a
  // from the vertical lands at tan a + tan b + tan a (sin a = 1.5 sin b) with weight 1 (the
  // radiance factors of the two crossings cancel), or (1 - R_a)(1 - R_b) with Fresnel; one ray
  // per channel with three indices. The eye rays and the path tracer follow rays so.
  for (const bool fresnel : {false, true}) {
    for (const double angle : {0.0, 0.3, 0.9}) {
      test::SceneBuilder b;
      Refraction glass;
      glass.ior = Rgb(1.5, 1.5, 1.5);
      glass.fresnel = fresnel;
      b.box({-50, -50, 1}, {50, 50, 2}, b.material("glass", glass));
      b.rectangle(-100, 100, -100, 100, 3, true, b.material("ceiling", Rgb::Zero(), Rgb::Ones()));
      const RayCaster caster(b.scene());
      const Vec3 d(std::sin(angle), 0, std::cos(angle));
      std::vector<std::pair<Vec3, Rgb>> ceiling;
      caster.follow({Vec3::Zero(), d}, RayCaster::limits_of(b.scene()), 1e-9,
                    [&](const Hit& hit, const Rgb& weight, int) {
                      if (hit.point.z() > 2.5) ceiling.emplace_back(hit.point, weight);
                    });
      const double inside = std::asin(std::sin(angle) / 1.5);
      const double x = 2 * std::tan(angle) + std::tan(inside);
      // Without Fresnel only the refracted ray goes on; with it the reflected ones end below.
      ASSERT_EQ(ceiling.size(), 1u) << "angle " << angle;
      EXPECT_NEAR(ceiling[0].first.x(), x, 1e-9) << "angle " << angle;
      const double passed = 1 - test::hecht_reflectance(angle, 1.5).unpolarised();
      const double expected = fresnel ? passed * passed : 1.0;
      EXPECT_NEAR(ceiling[0].second[0], expected, 1e-12) << "angle " << angle;
    }
  }
}

}  // namespace
}  // namespace rad
