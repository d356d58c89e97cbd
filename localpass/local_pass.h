#pragma once
/// The error-bounded local pass (paper 004 §4.3, Fig. 6; DESIGN.md §3 eqs. 7-10): at a point,
/// gather exactly from the solution's elements voxel by voxel in order of decreasing bound, and
/// stop as soon as what may remain is below the tolerance, with a certified bound on the error.
///
/// Why the bound is certified. Every gather here sees every face as an occluder (from both
/// sides) and lets only the selected voxels' faces radiate, so it returns exactly
///   H_S = sum over selected faces A of B(A) FF(x, visible part of A),
/// and H = H_S + sum over the other faces of the same terms, each >= 0. The faces of an
/// unselected voxel v are visible, if at all, inside the silhouette of their box and radiate at
/// most the largest radiosity among those of them that can light x, so their terms sum to at
/// most Bound(x, v) (eq. 8, octree/octree.h). Hence
///   0 <= H - H_S <= R = sum over unselected voxels of Bound(x, v),
/// per channel. Vertex tracing gets this by tracing every face as an occluder. The hemisphere
/// projects incrementally instead, and projects with each selected voxel every voxel that may
/// hide it (004's SolveVisibility: the bounding-sphere cones overlap and the other reaches
/// nearer), so the selected faces' visible parts are exact there too; and as the unselected
/// faces can only show outside those parts, with C the form factor they cover,
///   H - H_S <= (largest unselected radiosity toward x) * (1 - C),
/// the certified form of 004's eq. 10, and R is the smaller of the two. The error has one sign.
/// The pass reports H_S + R/2 with the bound R/2, and stops when
///   max_c R_c / 2 <= tolerance * max_c (H_S + R/2)_c,
/// so the relative error (against the brightest channel) is at most the tolerance.
#include <optional>
#include <vector>

#include "localpass/emitting_faces.h"
#include "localpass/hemisphere_gather.h"
#include "localpass/vertex_tracing.h"
#include "octree/octree.h"
#include "scene/scene.h"

namespace rad {

enum class ExactMethod { hemisphere, vertex };

struct LocalPassResult {
  Rgb irradiance = Rgb::Zero();  ///< H(x) estimate [W/m^2]: the exact part plus half the remainder bound
  Rgb bound = Rgb::Zero();       ///< Certified: |H(x) - irradiance| <= bound, per channel
  int emitting = 0;              ///< Faces gathered exactly (radiating in some gather)
  int projected = 0;             ///< Faces projected (hemisphere: emitting + possible occluders;
                                 ///< vertex tracing: the radiating faces, summed over its traces)
  int voxels = 0;                ///< Leaf voxels selected
  int gathers = 0;               ///< Exact gathers run (0 when nothing can light x)
};

/// The octree's items: one per face, with its polygon's normal and its exitance.
std::vector<OctreeItem> octree_items(const Scene& scene, const std::vector<EmittingFace>& faces);

class LocalPass {
 public:
  /// `faces` are typically faces_from_solution (every element radiates its radiosity).
  LocalPass(const Scene& scene, std::vector<EmittingFace> faces, ExactMethod method,
            const OctreeSettings& settings = {});

  /// Irradiance at x for unit normal n, to the given relative tolerance (0: exact, one gather
  /// with every face radiating). Thread-safe.
  LocalPassResult gather(const Vec3& x, const Vec3& n, double tolerance) const;

  const Octree& octree() const { return octree_; }
  int face_count() const { return static_cast<int>(faces_.size()); }

 private:
  /// One exact gather from scratch with the `emitting` faces radiating (vertex tracing; the
  /// hemisphere only at tolerance 0, with every face radiating: it is incremental otherwise).
  Rgb gather_exact(const Vec3& x, const Vec3& n, const std::vector<char>& emitting) const;

  std::vector<EmittingFace> faces_;
  ExactMethod method_;
  Octree octree_;
  std::optional<HemisphereGatherer> hemisphere_;
  std::optional<VertexTracer> tracer_;
  std::vector<Vec3> leaf_centre_;   ///< Per voxel: centre and radius of the sphere around its bounds
  std::vector<double> leaf_radius_;
};

}  // namespace rad
