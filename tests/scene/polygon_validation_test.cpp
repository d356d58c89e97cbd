#include "scene/polygon_validation.h"

#include <gtest/gtest.h>

#include "scene/error.h"

namespace rad {
namespace {

/// Runs make_polygons and returns the InputError message, or "" when it succeeded.
std::string error_of(std::vector<Vec3> vertices) {
  std::vector<std::string> warnings;
  try {
    make_polygons(std::move(vertices), "f.json: objects[0] polygon 3", 0, 0, 3, warnings);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PolygonValidation, AcceptsPlanarPolygonAndComputesNormalAndArea) {
  std::vector<std::string> warnings;
  const auto result =
      make_polygons({{0, 2, 0}, {0, 2, 3}, {4, 2, 3}, {4, 2, 0}}, "w", 1, 2, 5, warnings);
  ASSERT_EQ(result.size(), 1u);
  EXPECT_TRUE(warnings.empty());
  EXPECT_NEAR(result[0].area, 12.0, 1e-14);
  EXPECT_NEAR(result[0].normal.y(), 1.0, 1e-15);  // counter-clockwise seen from +y
  EXPECT_EQ(result[0].material, 1);
  EXPECT_EQ(result[0].object, 2);
  EXPECT_EQ(result[0].source_index, 5);
  EXPECT_EQ(result[0].triangle, -1);
}

TEST(PolygonValidation, RejectsEachErrorClassNamingTheElement) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    std::vector<Vec3> vertices;
    std::string expected;
  } cases[] = {
      {{{0, 0, 0}, {1, 0, 0}}, "has 2 vertices"},
      {{{0, 0, 0}, {1, 0, 0}, {1, nan, 0}}, "vertex 2 is not finite"},
      {{{0, 0, 0}, {inf, 0, 0}, {1, 1, 0}}, "vertex 1 is not finite"},
      {{{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 0, 0}}, "2 distinct vertices"},
      {{{0, 0, 0}, {1, 1, 1}, {3, 3, 3}}, "zero area"},
      {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, 0}}, "not planar"},
      {{{0, 0, 0}, {2, 0, 0}, {0.5, 1.5, 0}, {1, -1, 0}, {1.5, 1.5, 0}}, "self-intersecting"},
  };
  for (const Case& c : cases) {
    const std::string message = error_of(c.vertices);
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << "expected '" << c.expected << "', got '" << message << "'";
    EXPECT_EQ(message.rfind("f.json: objects[0] polygon 3: ", 0), 0u) << message;
  }
}

TEST(PolygonValidation, SplitsSlightlyNonPlanarPolygonIntoTrianglesWithWarning) {
  // The Cornell box's left wall: 3.2 mm of twist over a 559 x 549 mm quad.
  std::vector<std::string> warnings;
  const auto result =
      make_polygons({{552.8, 0, 0}, {549.6, 0, 559.2}, {556, 548.8, 559.2}, {556, 548.8, 0}},
                    "left", 0, 5, 0, warnings);
  ASSERT_EQ(result.size(), 2u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("split into 2 triangles"), std::string::npos) << warnings[0];
  double area = 0;
  for (const Polygon& p : result) {
    area += p.area;
    EXPECT_LT(p.normal.x(), -0.99) << "the red wall faces -x, into the box";
    EXPECT_EQ(p.source_index, 0);
  }
  EXPECT_EQ(result[0].triangle, 0);
  EXPECT_EQ(result[1].triangle, 1);
  EXPECT_NEAR(area, 559.2 * 548.8, 0.01 * 559.2 * 548.8);
}

TEST(PolygonValidation, MergesRepeatedVerticesWithWarning) {
  std::vector<std::string> warnings;
  const auto result = make_polygons(
      {{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}}, "w", 0, 0, 0, warnings);
  ASSERT_EQ(result.size(), 1u);
  EXPECT_EQ(result[0].vertices.size(), 4u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("merged 2"), std::string::npos) << warnings[0];
}

TEST(PolygonValidation, AcceptsTinyAndHugePolygons) {
  for (double scale : {1e-9, 1e-6, 1.0, 1e6, 1e9}) {
    std::vector<Vec3> square;
    for (const Vec3& v : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}) {
      square.push_back(Vec3(5, 5, 5) + scale * v);  // offset: tiny polygons far from the origin
    }
    EXPECT_EQ(error_of(square), "") << "scale " << scale;
  }
}

}  // namespace
}  // namespace rad
