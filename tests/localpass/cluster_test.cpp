// The local pass's clusters (localpass/cluster_tree.h): the tree covers every face once with
// outlines that hold them, the solver's mesh gives outlines the faces fill, and a partly hidden
// cluster's interval holds where the hidden part is the bright one.
#include <gtest/gtest.h>

#include "geometry/lambert.h"
#include "localpass/cluster_tree.h"
#include "localpass/local_pass.h"
#include "scene/scene_loader.h"
#include "tests/coarse_solution.h"

namespace rad {
namespace {

/// Whether p lies in the convex planar polygon (counter-clockwise about normal), to tolerance.
bool inside(const std::vector<Vec3>& outline, const Vec3& normal, const Vec3& p, double tolerance) {
  for (size_t i = 0; i < outline.size(); ++i) {
    const Vec3 edge = outline[(i + 1) % outline.size()] - outline[i];
    if (normal.cross(edge).normalized().dot(p - outline[i]) < -tolerance) return false;
  }
  return true;
}

TEST(ClusterTree, CoversEveryFaceOnceWithOutlinesThatHoldThem) {
  const test::SolvedScene& s = test::coarse_cornell();
  const ClusterTree tree(s.faces);
  std::vector<int> seen(s.faces.size(), 0);
  for (const int f : tree.faces()) ++seen[f];
  EXPECT_EQ(std::ranges::count(seen, 1), static_cast<long>(s.faces.size()));
  const double tolerance = s.scene.tolerance().pad;
  int inner = 0, filled = 0;
  for (const Cluster& c : tree.clusters()) {
    for (int i = 0; i < c.face_count; ++i) {
      const EmittingFace& face = s.faces[tree.faces()[c.first_face + i]];
      ASSERT_EQ(face.polygon, c.polygon);
      for (const Vec3& v : face.vertices) ASSERT_TRUE(inside(c.outline, c.normal, v, tolerance));
      ASSERT_TRUE(((face.exitance - c.bmin).array() >= 0).all());
      ASSERT_TRUE(((c.bmax - face.exitance).array() >= 0).all());
      ASSERT_TRUE(((c.bspread - (face.exitance - c.bmean).cwiseAbs()).array() >= -1e-15).all());
    }
    if (c.is_leaf()) continue;
    ++inner;
    filled += c.fills_outline;
    const Cluster& a = tree.clusters()[c.children[0]];
    const Cluster& b = tree.clusters()[c.children[1]];
    EXPECT_EQ(a.face_count + b.face_count, c.face_count);
    EXPECT_EQ(a.first_face, c.first_face);
  }
  // The solver's patch grids cut cleanly: nearly every cluster is a block its faces fill.
  EXPECT_GT(filled, 0.9 * inner) << filled << " of " << inner;
}

TEST(LocalPass, BoundHoldsWhereTheHiddenHalfOfAClusterIsTheBright) {
  // A wall of two faces, bright (1) and dark (0.2), and a screen that hides the bright one
  // from x. The exact value is the dark face's alone; a lower bound from the cluster's mean
  // radiosity (valid only for what is seen whole) would exceed it.
  const Scene scene = parse_scene(R"({
    "materials": {"white": {"reflectance": [0.5, 0.5, 0.5]}},
    "objects": [
      {"name": "wall", "material": "white", "polygons": [[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]]},
      {"name": "screen", "material": "white", "polygons": [[[-1,-1,5],[0.5,-1,5],[0.5,2,5],[-1,2,5]]]}
    ]})",
                                  "two-faces.json");
  const auto face = [&](int polygon, std::vector<Vec3> vertices, double b) {
    return EmittingFace{polygon, std::move(vertices), Rgb::Constant(b), std::vector<bool>(4, false),
                        scene.polygons[polygon].normal};
  };
  const std::vector<EmittingFace> faces = {
      face(0, {{0, 0, 0}, {0.5, 0, 0}, {0.5, 1, 0}, {0, 1, 0}}, 1.0),
      face(0, {{0.5, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.5, 1, 0}}, 0.2),
      face(1, scene.polygons[1].vertices, 0.0)};
  const LocalPass pass(scene, faces, Method::hemisphere);
  const Vec3 x(0.5, 0.5, 10), n(0, 0, -1);
  const Rgb exact = pass.gather(x, n, 0).irradiance;
  EXPECT_NEAR(exact[0], 0.2 * point_polygon_form_factor(x, n, faces[1].vertices), 1e-15);
  for (const double tolerance : {0.5, 0.3, 0.2, 0.1, 0.01}) {
    const LocalPassResult r = pass.gather(x, n, tolerance);
    EXPECT_LE((r.irradiance - exact).cwiseAbs().maxCoeff(), r.bound.maxCoeff() * (1 + 1e-12))
        << "tolerance " << tolerance << ": " << r.irradiance.transpose() << " +- "
        << r.bound.transpose() << ", exact " << exact.transpose();
  }
}

}  // namespace
}  // namespace rad
