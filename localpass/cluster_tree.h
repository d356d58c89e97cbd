#pragma once
/// The local pass's clusters: per scene polygon, a binary tree over its faces, each node a set
/// of faces with a convex outline that holds them (004 §4.2's "a voxel's polygons", made tight:
/// clusters follow the polygon, not the octree's cells). A cluster seen whole from x gives an
/// interval that surely holds its exact contribution with one Lambert formula instead of one
/// per face (localpass/local_pass.h proves it); the pass refines the widest interval.
///
/// Nodes are split along clean cuts where the mesh has them: a line through a face edge with
/// every face on one side of it. A patch grid (the solver's mesh) has one along every grid
/// line, so each node down to the patches is a block of grid cells whose union is its convex
/// outline exactly (the area test below confirms it, node by node); inside a patch, the
/// element quadtree's mid-lines cut it. Where no clean cut exists, the node splits at the
/// median of its face centroids and its children may not fill their outlines: they then give
/// only an upper bound until they are refined.
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "geometry/emitting_face.h"

namespace rad {

struct Cluster {
  int polygon = -1;
  int face = -1;                           ///< A single face (a leaf of the tree), or -1.
  std::array<int, 2> children = {-1, -1};  ///< Inner nodes: the two halves.
  std::vector<Vec3> outline;    ///< Convex hull of its faces' vertices, counter-clockwise
                                ///< about the normal, with vertices taken from the faces.
  Vec3 normal = Vec3::UnitZ();  ///< Its polygon's front normal.
  /// The faces fill the outline: outline area = sum of face areas, to 1e-9. Then
  /// FF(x, union of the faces) >= FF(x, outline) - gap_area / (pi h^2), h the distance from x
  /// to the plane, since the part of the outline the faces leave out has at most gap_area.
  bool fills_outline = false;
  double gap_area = 0;  ///< |outline area - face area| plus 1e-12 of the outline's area.
  Rgb bmin = Rgb::Zero(), bmax = Rgb::Zero();  ///< Per channel over its faces' exitance.
  double face_area = 0;                        ///< Sum of its faces' areas
  Rgb bmean = Rgb::Zero();                     ///< Area-weighted mean exitance of its faces
  Rgb bspread = Rgb::Zero();  ///< max over its faces of |exitance - bmean|, per channel
  /// sum over its faces of area |exitance - bmean|, per channel (<= bspread face_area)
  Rgb babs = Rgb::Zero();
  Vec3 center = Vec3::Zero();  ///< Area centroid of its faces (inside the outline)
  double radius = 0;           ///< Largest distance from the center to the outline
  /// Column c: sum over its faces of area (exitance_c - bmean_c) (centroid - center), the
  /// first moment of its radiosity about the mean (zero for a single face).
  Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
  Eigen::AlignedBox3d box;  ///< Around the outline.
  int face_count = 0;
  int first_face = 0;  ///< Its faces are ClusterTree::faces()[first_face, first_face + face_count)

  bool is_leaf() const { return face >= 0; }
};

class ClusterTree {
 public:
  /// Faces must be convex (EmittingFace's contract); faces of one polygon share its plane and
  /// do not overlap (a mesh of it). Cost O(F log F) per polygon, times the candidate cuts tried.
  explicit ClusterTree(const std::vector<EmittingFace>& faces);

  const std::vector<Cluster>& clusters() const { return clusters_; }
  /// One root per polygon that has faces, in polygon order.
  const std::vector<int>& roots() const { return roots_; }
  /// Face indices in depth-first order of the tree: each cluster's faces are a range of it.
  const std::vector<int>& faces() const { return face_order_; }

 private:
  struct Flat;  // the faces of one polygon in its plane's 2D coordinates
  int build(const Flat& flat, std::vector<int> members);

  std::vector<Cluster> clusters_;
  std::vector<int> roots_;
  std::vector<int> face_order_;
};

}  // namespace rad
