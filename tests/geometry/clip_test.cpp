// The one clipping routine (geometry/clip.h) against hand-worked cases: which vertices are kept,
// where crossings land, which input edge each output edge lies on (vertex tracing's silhouette
// flags depend on it), and no repeated vertex where a vertex lies on the plane.
#include "geometry/clip.h"

#include <gtest/gtest.h>

#include <vector>

namespace rad {
namespace {

struct Clipped {
  std::vector<Vec3> points;
  std::vector<int> edges;
};

Clipped clip_z(const std::vector<Vec3>& loop) {
  Clipped out;
  clip_loop(
      loop, loop.size(), [](const Vec3& p) { return p.z(); }, interpolated_crossing,
      [&](const Vec3& p, int edge) {
        out.points.push_back(p);
        out.edges.push_back(edge);
      });
  return out;
}

TEST(Clip, StraddlingSquareKeepsTheUpperHalfWithTheCutLabelled) {
  // A unit square in the xz-plane from z = -1 to z = 1: edges 0 (bottom), 1 (right), 2 (top), 3
  // (left).
  const std::vector<Vec3> square{{0, 0, -1}, {1, 0, -1}, {1, 0, 1}, {0, 0, 1}};
  const Clipped c = clip_z(square);
  ASSERT_EQ(c.points.size(), 4u);
  EXPECT_TRUE(c.points[0].isApprox(Vec3(1, 0, 0))) << c.points[0].transpose();
  EXPECT_EQ(c.points[1], Vec3(1, 0, 1));
  EXPECT_EQ(c.points[2], Vec3(0, 0, 1));
  EXPECT_TRUE(c.points[3].isApprox(Vec3(0, 0, 0))) << c.points[3].transpose();
  // Entering on edge 1 (its upper part), then edge 2, then edge 3 down to the plane, then the cut.
  EXPECT_EQ(c.edges, (std::vector<int>{1, 2, 3, kEdgeAlongCut}));
}

TEST(Clip, VertexOnThePlaneIsKeptOnceAndStartsTheCut) {
  // A triangle with one vertex on the plane and one below: no crossing point is made at the
  // on-plane vertex, and the edge leaving it runs along the cut.
  const std::vector<Vec3> triangle{{0, 0, 0}, {1, 0, -1}, {1, 0, 1}};
  const Clipped c = clip_z(triangle);
  ASSERT_EQ(c.points.size(), 3u);
  EXPECT_EQ(c.points[0], Vec3(0, 0, 0));
  EXPECT_EQ(c.edges[0], kEdgeAlongCut);
  EXPECT_TRUE(c.points[1].isApprox(Vec3(1, 0, 0)));
  EXPECT_EQ(c.edges[1], 1);
  EXPECT_EQ(c.points[2], Vec3(1, 0, 1));
  EXPECT_EQ(c.edges[2], 2);
}

TEST(Clip, WhollyInsideOrOutside) {
  const std::vector<Vec3> above{{0, 0, 1}, {1, 0, 1}, {0, 1, 2}};
  EXPECT_EQ(clip_to_halfspace(above, Vec3::Zero(), Vec3::UnitZ()), above);
  EXPECT_TRUE(clip_to_halfspace(above, Vec3::Zero(), -Vec3::UnitZ()).empty());
  // The half-space through another point: n . (p - point) >= 0.
  EXPECT_EQ(clip_to_halfspace(above, Vec3(0, 0, 1.5), Vec3::UnitZ()).size(), 3u);
}

}  // namespace
}  // namespace rad
