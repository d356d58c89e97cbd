// Cutting polygons along their contact lines (radiosity/contact_cuts.h): the pieces tile the
// polygon, none straddles a footprint, and only what rises from the front cuts.
#include "radiosity/contact_cuts.h"

#include <gtest/gtest.h>

#include <cmath>

#include "radiosity/mesher.h"
#include "tests/scene_builder.h"

namespace rad {
namespace {

using test::SceneBuilder;

/// The faces of a box standing on z = 0 with its footprint the convex quad `foot`
/// (counter-clockwise from above) and height h: four sides facing out and the top.
void add_block(SceneBuilder& b, const std::vector<Vec3>& foot, double h, int material) {
  for (size_t i = 0; i < foot.size(); ++i) {
    const Vec3& a = foot[i];
    const Vec3& c = foot[(i + 1) % foot.size()];
    b.polygon({a, c, c + Vec3(0, 0, h), a + Vec3(0, 0, h)}, material);
  }
  std::vector<Vec3> top;
  for (const Vec3& v : foot) top.push_back(v + Vec3(0, 0, h));
  b.polygon(top, material);
}

double area_of(const std::vector<Vec3>& corners) {
  double area;
  Vec3 centroid;
  element_geometry(corners, &area, &centroid);
  return area;
}

/// True when p lies inside the convex footprint (counter-clockwise from above), by more than
/// `margin`; `outside` asks for outside by more than margin.
bool strictly_inside(const std::vector<Vec3>& foot, const Vec3& p, double margin) {
  for (size_t i = 0; i < foot.size(); ++i) {
    const Vec3 e = foot[(i + 1) % foot.size()] - foot[i];
    if (e.cross(p - foot[i]).z() / e.norm() <= margin) return false;
  }
  return true;
}
bool strictly_outside(const std::vector<Vec3>& foot, const Vec3& p, double margin) {
  for (size_t i = 0; i < foot.size(); ++i) {
    const Vec3 e = foot[(i + 1) % foot.size()] - foot[i];
    if (e.cross(p - foot[i]).z() / e.norm() < -margin) return true;
  }
  return false;
}

/// Every piece is planar in z = 0, convex and counter-clockwise from +z, the areas sum to the
/// floor's, and no piece has points both strictly inside and strictly outside the footprint.
void expect_tiling_without_straddling(const std::vector<std::vector<Vec3>>& pieces,
                                      double floor_area, const std::vector<Vec3>& foot) {
  ASSERT_FALSE(pieces.empty());
  double total = 0;
  for (const auto& piece : pieces) {
    ASSERT_GE(piece.size(), 3u);
    total += area_of(piece);
    bool in = false, out = false;
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& v : piece) centroid += v / static_cast<double>(piece.size());
    for (size_t i = 0; i < piece.size(); ++i) {
      EXPECT_NEAR(piece[i].z(), 0, 1e-12);
      const Vec3& a = piece[i];
      const Vec3& b = piece[(i + 1) % piece.size()];
      const Vec3& c = piece[(i + 2) % piece.size()];
      EXPECT_GT((b - a).cross(c - b).z(), 0) << "not convex, or clockwise";
      // Points across the piece: its corners pulled towards the centroid, and the centroid.
      for (const Vec3& p : {Vec3(0.9 * a + 0.1 * centroid), centroid}) {
        in = in || strictly_inside(foot, p, 1e-9);
        out = out || strictly_outside(foot, p, 1e-9);
      }
    }
    EXPECT_FALSE(in && out) << "a piece straddles the footprint";
  }
  EXPECT_NEAR(total, floor_area, 1e-9 * floor_area);
}

TEST(ContactCuts, ABlockOnTheFloorCutsItAlongItsFootprint) {
  SceneBuilder b;
  const int white = b.material("white", Rgb::Constant(0.5), Rgb::Zero());
  const int floor = b.rectangle(0, 4, 0, 4, 0, false, white);
  const std::vector<Vec3> foot{{1, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}};
  add_block(b, foot, 1, white);
  const auto pieces = contact_pieces(b.scene(), floor);
  expect_tiling_without_straddling(pieces, 16, foot);
  // The block's own faces: the floor meets them on their outlines only.
  for (int face = floor + 1; face < static_cast<int>(b.scene().polygons.size()); ++face)
    EXPECT_TRUE(contact_pieces(b.scene(), face).empty()) << "face " << face;
}

TEST(ContactCuts, ARotatedBlockAsInTheCornellBox) {
  SceneBuilder b;
  const int white = b.material("white", Rgb::Constant(0.5), Rgb::Zero());
  const int floor = b.rectangle(0, 556, 0, 559, 0, false, white);
  const std::vector<Vec3> foot{{130, 65, 0}, {290, 114, 0}, {240, 272, 0}, {82, 225, 0}};
  add_block(b, foot, 165, white);
  expect_tiling_without_straddling(contact_pieces(b.scene(), floor), 556.0 * 559, foot);
}

TEST(ContactCuts, AConcaveFloorIsCutPieceByPiece) {
  SceneBuilder b;
  const int white = b.material("white", Rgb::Constant(0.5), Rgb::Zero());
  // An L: [0,4]^2 without [2,4] x [2,4]; the block straddles the inner corner's diagonal.
  const int floor =
      b.polygon({{0, 0, 0}, {4, 0, 0}, {4, 2, 0}, {2, 2, 0}, {2, 4, 0}, {0, 4, 0}}, white);
  const std::vector<Vec3> foot{{0.5, 0.5, 0}, {1.7, 0.5, 0}, {1.7, 1.5, 0}, {0.5, 1.5, 0}};
  add_block(b, foot, 1, white);
  expect_tiling_without_straddling(contact_pieces(b.scene(), floor), 12, foot);
}

TEST(ContactCuts, APolygonThroughTheFloorCutsItAndOnlyWhatRisesInFrontCuts) {
  SceneBuilder b;
  const int white = b.material("white", Rgb::Constant(0.5), Rgb::Zero());
  const int floor = b.rectangle(0, 4, 0, 4, 0, false, white);
  // A wall through the floor along x = 3, y in [1, 3]: the floor is cut along it.
  b.polygon({{3, 1, -1}, {3, 3, -1}, {3, 3, 1}, {3, 1, 1}}, white);
  const auto pieces = contact_pieces(b.scene(), floor);
  ASSERT_GE(pieces.size(), 2u);
  double total = 0;
  for (const auto& piece : pieces) {
    total += area_of(piece);
    bool left = false, right = false;
    for (const Vec3& v : piece) left = left || v.x() < 3 - 1e-9, right = right || v.x() > 3 + 1e-9;
    EXPECT_FALSE(left && right);
  }
  EXPECT_NEAR(total, 16, 1e-12);

  // Nothing rising in front: a polygon wholly behind the floor, one in its plane, one far
  // away, and the walls around it standing on its outline.
  SceneBuilder c;
  const int m = c.material("white", Rgb::Constant(0.5), Rgb::Zero());
  const int alone = c.rectangle(0, 4, 0, 4, 0, false, m);
  c.polygon({{1, 1, -2}, {2, 1, -2}, {2, 1, -0.5}, {1, 1, -0.5}}, m);  // below
  c.rectangle(1, 2, 1, 2, 0, true, m);                                 // in the plane, facing down
  c.polygon({{9, 1, 0}, {9, 3, 0}, {9, 3, 1}, {9, 1, 1}}, m);          // beyond its edge
  c.polygon({{0, 0, 0}, {0, 4, 0}, {0, 4, 2}, {0, 0, 2}}, m);          // on its outline
  EXPECT_TRUE(contact_pieces(c.scene(), alone).empty());
}

TEST(ContactCuts, PatchesOfACutFloorTileItAndNoneStraddles) {
  SceneBuilder b;
  const int white = b.material("white", Rgb::Constant(0.5), Rgb::Zero());
  const int floor = b.rectangle(0, 4, 0, 4, 0, false, white);
  const std::vector<Vec3> foot{{1.3, 0.7, 0}, {2.4, 1.1, 0}, {2.0, 2.2, 0}, {0.9, 1.8, 0}};
  add_block(b, foot, 1, white);
  std::vector<std::vector<Vec3>> floor_patches;
  for (const Patch& p : make_patches(b.scene(), 0.3)) {
    if (p.polygon == floor) floor_patches.push_back(p.corners);
  }
  expect_tiling_without_straddling(floor_patches, 16, foot);
}

}  // namespace
}  // namespace rad
