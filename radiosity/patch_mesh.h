#pragma once
/// The solution's leaf elements as one conforming OpenMesh polygon mesh, for display, files and
/// (later) vertex tracing.
///
/// Adaptive refinement leaves T-junctions: a coarse element beside finer ones has neighbours'
/// corners in the middle of its sides. Here those corners become vertices of the coarse face
/// too (collinear ones), so every edge is shared by exactly the faces on its two sides and the
/// half-edge structure is conforming. Interpolation by mean value coordinates is linear along
/// each edge between consecutive vertices, so values agree on both sides of every edge: no
/// cracks in Gouraud display.
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <optional>
#include <vector>

#include "radiosity/solution.h"

namespace rad {

struct PatchMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
};
/// Faces are leaf elements; vertices are shared within a scene polygon (not across polygons).
using PatchMesh = OpenMesh::PolyMesh_ArrayKernelT<PatchMeshTraits>;

/// The conforming element mesh of a solution. Face f is the solution's f-th leaf (in index
/// order); its vertices run counter-clockwise from the front, T-vertices included.
class ElementMesh {
 public:
  /// Builds the mesh; `tolerance` (scene units) merges coincident corners and finds
  /// T-vertices. Cost: O(leaves * vertices on a side) per polygon, via a spatial hash.
  ElementMesh(const Solution& solution, double tolerance);

  const PatchMesh& mesh() const { return mesh_; }
  int face_count() const { return static_cast<int>(face_element_.size()); }
  /// The element (index into Solution::elements) of face f.
  int element(int face) const { return face_element_[face]; }
  /// The face's vertex positions, counter-clockwise, T-vertices included.
  std::vector<Vec3> face_points(int face) const;
  /// The face's vertex indices (OpenMesh vertex handles' indices).
  std::vector<int> face_vertices(int face) const;

  /// The radiosity at face f's centroid predicted by the least-squares plane
  /// B(u, v) = a + b u + c v through its mesh neighbours' radiosities at their centroids (in
  /// the face's plane, around its centroid: the prediction is a). None with fewer than three
  /// neighbours, or neighbours in a line.
  std::optional<Rgb> neighbour_plane_at(const Solution& solution, int face) const;

  /// Gouraud vertex values: per vertex, the area-weighted mean radiosity of the faces around
  /// it (+ rho * ambient when `with_ambient`). Indexed by vertex.
  std::vector<Rgb> vertex_radiosity(const Solution& solution,
                                    const std::vector<Rgb>& face_reflectance,
                                    bool with_ambient) const;

 private:
  PatchMesh mesh_;
  std::vector<int> face_element_;
};

/// Interpolates vertex values at a point of a planar polygon by mean value coordinates
/// (Floater 2003) in the polygon's plane: linear along every edge, exact at vertices, smooth
/// inside, defined for concave polygons and collinear (T-junction) vertices. A point on an edge
/// takes the linear interpolation of that edge's ends.
Rgb interpolate_mean_value(const std::vector<Vec3>& polygon, const std::vector<Rgb>& values,
                           const Vec3& normal, const Vec3& point);

}  // namespace rad
