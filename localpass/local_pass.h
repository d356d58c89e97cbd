#pragma once
/// The error-bounded local pass (paper 004 §4.3, Fig. 6; DESIGN.md §3 eqs. 7-10): at a point,
/// sum the solution's faces' contributions H = sum_A B(A) FF(x, visible part of A) as a sum of
/// terms, each known to lie in an interval, refine the widest term until the half-width of the
/// total is within the tolerance, and report the middle with a certified bound.
///
/// The terms are clusters of faces of one polygon (localpass/cluster_tree.h), from whole
/// polygons down to single faces. Whether something may hide a cluster from x is the culling's
/// question (localpass/occlusion_culling.h: the blocking polygons, by plane and shaft tests).
///
/// Why each interval holds (per channel; FF_A = FF(x, A above x's horizon), sum over the
/// cluster's faces; F = FF(x, outline) by Lambert's formula; the faces do not overlap):
///  - sum FF_A = FF(x, union of the faces) <= F, since the union lies in the convex outline.
///    When the faces fill the outline, sum FF_A >= F - gap_area / (pi h^2), h the height of x
///    over the plane (the kernel is at most 1/(pi r^2) <= 1/(pi h^2)).
///  - zeroth order: bmin sum FF_A <= term <= bmax sum FF_A, when seen whole.
///  - first order, seen whole: term = bmean sum FF_A + sum (B_A - bmean)(FF_A - area_A kmid),
///    as sum (B_A - bmean) area_A = 0 for the area-weighted mean bmean; with the kernel in
///    [kmin, kmax] on the outline, |FF_A - area_A kmid| <= area_A (kmax - kmin) / 2, so the
///    term is within babs (kmax - kmin) / 2 of bmean sum FF_A (babs = sum |B_A - bmean| area_A).
///  - second order, seen whole and wholly above x's horizon: with the kernel's expansion
///    k(y) = k(c) + g . (y - c) + R(y), |R| <= remainder on the outline (localpass/
///    cluster_bounds.h), FF_A - area_A k(c) = g . area_A (c_A - c) + integral of R over A, so the
///    term is within babs remainder of bmean sum FF_A + g . moment (moment = sum (B_A - bmean)
///    area_A (c_A - c), per channel).
///  - hidden parts only lower a term, so every upper end above holds for any cluster; one that
///    may be hidden gets the lower end 0, or, with V = FF(x, visible part of the outline) from
///    an exact visibility query against its blocking polygons (hemisphere/blocker_surface.h),
///    bmin (V - gap term) <= term <= bmax V (the same argument on the visible parts), and the
///    term is within babs kmax of bmean sum FF'_A (FF'_A of the visible parts, <= area_A kmax).
///  - filters (000 §2.2): a face's term is B_A times the integral over A of the kernel times
///    the product of the transmittances crossed on the way (0 through an opaque polygon), so it
///    still lies in [0, B_A FF_A] and is exact when nothing lies in its shaft. The visibility
///    query treats every blocker as opaque, so through filters it is asked twice: with them
///    (V, every weight taken as 0: the lower ends) and without them (V_hi, every weight as 1:
///    the upper ends, bmax V_hi and bmean V_hi + babs kmax); the weighted visible form factor
///    lies between. A face seen through a filter is never exact by a query.
///  - a single face: B FF(x, face) when seen whole (Lambert); B V by the query (hemisphere);
///    otherwise [0, B FF] until vertex tracing gathers it exactly, in steps of one session
///    with the faces of its blocking polygons that meet its shaft.
/// With L and U the sums of the lower and upper ends, L <= H <= U; the pass reports (L + U) / 2
/// with the bound (U - L) / 2 and stops when max_c bound_c <= tolerance * max_c value_c, so
/// the relative error (against the brightest channel) is at most the tolerance. At tolerance 0
/// every cluster is refined to its faces: every term is exact and the bound is 0.
#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "geometry/emitting_face.h"
#include "geometry/exact_gatherer.h"
#include "geometry/tolerance.h"
#include "localpass/cluster_tree.h"
#include "localpass/method.h"
#include "localpass/occlusion_culling.h"
#include "localpass/point_light_visibility.h"
#include "localpass/visible_set.h"
#include "octree/octree.h"
#include "scene/scene.h"
#include "specular/glossy_transfer.h"

namespace rad {

struct RefractionPath;

struct LocalPassSettings {
  OctreeSettings octree;
  /// Longest chain of plane-mirror reflections gathered (000 §3): 0 ignores mirrors (their
  /// diffuse part still radiates), 1 gathers each mirror's reflection, 2 also reflections of
  /// reflections, ... Each chain of k mirrors is unfolded into a scene of k + 1 copies of the
  /// faces (specular/mirror_images.h), and the number of chains grows like
  /// (mirror pieces facing each other)^depth. Unset: the scene's (Scene::mirror_depth).
  std::optional<int> mirror_depth;
  /// Longest chain of refracting facets gathered through (000 §4): 0 ignores refraction (the
  /// interfaces are opaque), 2 sees through a convex block. Unset: the scene's
  /// (Scene::refraction_depth).
  std::optional<int> refraction_depth;
  /// The refraction heuristic's accuracy knob (specular/refraction_images.h, facet_pieces and
  /// RefractionPath::traced): a chain's first facet is split until, along the rays from x
  /// through each piece refracted on through the chain's other facets, the depth ratio at every
  /// facet varies by at most this much; each piece's angles are those of its centroid's ray.
  /// Infinite: one angle per facet on the centroid path, the paper's method.
  double refraction_tolerance = std::numeric_limits<double>::infinity();
  /// At most this many pieces of a chain's first facet.
  int refraction_max_pieces = 64;
  /// Skip paths whose later facets' images lie outside the earlier ones' (000 §5's beams); false:
  /// every path (the same values).
  bool refraction_culling = true;
  /// Glossy transfer (paper 003, specular/glossy_transfer.h): the scatterers' and emitters'
  /// splits and the hierarchy's cut. `glossy_transfer` false leaves it out.
  GlossySettings glossy;
  bool glossy_transfer = true;
  /// Culling beams (000 §5): skip a mirror at points that cannot see anything radiating
  /// through it. false: every mirror at every point in front of it (the same values).
  bool mirror_culling = true;
  /// false: no shaft culling; every face that can light x goes to the gatherer at once with
  /// every face as an occluder (the naive exact gather, the baseline for measuring the culling;
  /// the same values at tolerance 0).
  bool occlusion_culling = true;
  /// Visibility culling (localpass/visible_set.h): at each point only the polygons it may see
  /// take part, as roots of the sum and as blockers (the same terms). Used when the scene has at
  /// least this many polygons; in a small scene (the Cornell box's 20) its walk cannot pay.
  /// 0: always.
  int visible_set_from = 64;
  /// The renderer's certified interpolation (localpass/tile_gather.h): cells of `tile` x `tile`
  /// pixels on one polygon are gathered at their corners and interpolated, each pixel's bound
  /// kept (render/irradiance_render.h). 0 or 1: every pixel on its own.
  int tile = 8;
  /// A cell interpolates only when its rest is less work than a corner's plain gather (at
  /// loose tolerances the plain gather is cheaper). false: wherever it can (for measuring the
  /// cells and testing their bound).
  bool tile_when_it_pays = true;
};

struct LocalPassResult {
  /// H(x) estimate [W/m^2]: the exact part plus half the remainder bound.
  Rgb irradiance = Rgb::Zero();
  Rgb bound = Rgb::Zero();   ///< Certified: |H(x) - irradiance| <= bound, per channel
  int gathered_exactly = 0;  ///< Faces gathered exactly (unoccluded or radiating in a gather)
  int unoccluded = 0;        ///< Of those, faces nothing can hide (Lambert's formula alone)
  int projected = 0;         ///< Faces projected (hemisphere: selected + possible occluders;
                             ///< vertex tracing: the same, summed over its traces)
  int clusters = 0;          ///< Cluster intervals computed (one Lambert formula each)
  int gathers = 0;           ///< Exact gathers run (0 when nothing can light x)
  int mirrored = 0;          ///< Gathers at unfolded receivers (000 §3): one per chain not culled
  int visible_polygons = 0;  ///< Polygons x may see (the visibility culling; 0 when it is off)
  /// 1 when a tile's interpolation gave the smooth part (localpass/tile_gather.h); the counts
  /// above are then those of the rest, gathered at x.
  int interpolated = 0;
  /// H(x) refracted through transparent polyhedra (000 §4), by the paper's heuristic: NOT
  /// covered by `bound`, and not in `irradiance`. The total is irradiance + refracted.
  Rgb refracted = Rgb::Zero();
  int refracted_images = 0;  ///< Exact gathers of refracted images (specular/refraction_images.h)
  /// H(x) from point sources reflected by glossy surfaces (003's beams): NOT covered by
  /// `bound`, and not in `irradiance`. The total is irradiance + refracted + glossy.
  Rgb glossy = Rgb::Zero();
  int glossy_beams = 0;  ///< Beams evaluated (specular/glossy_transfer.h)
};

/// The octree's items: one per face, with its polygon's normal and its exitance.
std::vector<OctreeItem> octree_items(const std::vector<EmittingFace>& faces);

class LocalPass {
 public:
  /// `faces` are typically faces_from_solution (every element radiates its radiosity);
  /// `method` picks the exact gatherer (hemisphere or vertex; Error for Monte Carlo).
  LocalPass(const Scene& scene, std::vector<EmittingFace> faces, Method method,
            const LocalPassSettings& settings = {});

  ~LocalPass();

  /// Irradiance at x for unit normal n, to the given relative tolerance (0: exact, every face
  /// that may be hidden radiating in one gather). With mirrors, H(x) = H_direct(x) + sum over
  /// chains c whose first mirror x faces of specular_c H_c(T_c x), each H_c a local pass of its
  /// own over c's unfolded scene (specular/mirror_images.h), at x unfolded with its normal;
  /// the bounds add with the same weights (each is certified for its own term). With n terms
  /// at x, each is gathered to tolerance / n, so the total still meets the stopping rule.
  /// Point lights add their direct light exactly (I cos / r^2 through the filters on the
  /// segment; localpass/point_light_visibility.h), with no width to the bound; their light by way
  /// of mirrors and refracting objects is not gathered. Light refracted through transparent
  /// polyhedra goes to `refracted`, apart (000 §4: each chain of facets x faces the first of,
  /// gathered exactly in its unfolded image at the centroid angles, specular/refraction_images.h).
  /// Thread-safe.
  LocalPassResult gather(const Vec3& x, const Vec3& n, double tolerance) const;

  /// Whether gather_tile interpolates: no mirrors, refraction or glossy transfer (their terms
  /// are gathered per point), and the culling on.
  bool interpolates() const;
  /// The renderer's interpolation cells, in pixels (LocalPassSettings::tile).
  int tile() const { return tile_; }
  /// At points of one plane (unit normal n) inside the quad of four `corners` (in order around
  /// it), with `at_corners` their gather(corner, n, tolerance): per point, a result certified
  /// as gather's is and meeting the same stopping rule, by the tile's interpolation where it
  /// holds and by gather elsewhere (localpass/tile_gather.h). Thread-safe.
  std::vector<LocalPassResult> gather_tile(const std::array<Vec3, 4>& corners,
                                           const std::array<LocalPassResult, 4>& at_corners,
                                           std::span<const Vec3> points, const Vec3& n,
                                           double tolerance) const;

  const Octree& octree() const { return octree_; }
  int face_count() const { return static_cast<int>(faces_.size()); }

 private:
  /// The faces' term plus `exact_part`, known exactly (point lights) the stopping rule counts.
  LocalPassResult gather_direct(const Vec3& x, const Vec3& n, double tolerance,
                                const Rgb& exact_part = Rgb::Zero()) const;
  /// What one cluster gather sums: by default every polygon's root cluster, with shaft
  /// culling; or given clusters, those in `whole` known to be seen whole from x (no culling),
  /// those in `culled` culled as roots are. `known_lo` <= part of H summed elsewhere <=
  /// `known_hi` (point lights: exact; a tile's interpolated part: an interval) is added, and
  /// the stopping rule counts it.
  struct GatherScope {
    const std::vector<int>* whole = nullptr;
    const std::vector<int>* culled = nullptr;
    Rgb known_lo = Rgb::Zero(), known_hi = Rgb::Zero();
    bool given_roots() const { return whole || culled; }
  };
  /// The error-bounded sum over the cluster tree (004 Fig. 6), localpass/cluster_gather.cpp.
  LocalPassResult gather_by_clusters(const Vec3& x, const Vec3& n, double tolerance,
                                     const GatherScope& scope) const;
  class ClusterGather;
  /// Certified interpolation over a tile (localpass/tile_gather.h).
  class TileGather;
  /// No culling: every face that can light x radiates in one gather, every face may hide it.
  LocalPassResult gather_plainly(const Vec3& x, const Vec3& n) const;

  std::vector<EmittingFace> faces_;
  /// The scene's polygons as convex pieces, by polygon: the blockers of the visibility queries
  /// (hemisphere/blocker_surface.h) that bound partly hidden clusters.
  std::vector<std::vector<EmittingFace>> blocker_pieces_;
  Tolerance tolerance_;
  /// Per polygon: 1 for filters, which the opaque visibility queries must not be asked about.
  std::vector<char> filter_polygon_;
  /// Hemisphere: partly hidden faces are queried too (the query is that method's projection).
  /// Vertex tracing gathers them in steps of its own session.
  bool faces_by_query_;
  bool occlusion_culling_;
  int tile_ = 0;
  bool tile_when_it_pays_ = true;
  Octree octree_;
  std::unique_ptr<ExactGatherer> gatherer_;
  OcclusionCulling culling_;
  ClusterTree clusters_;
  /// The visibility culling (null when off) and each polygon's root cluster (-1: no faces).
  std::unique_ptr<const VisibleSet> visible_set_;
  std::vector<int> root_of_polygon_;
  /// One chain of mirrors: its unfolded scene and the local pass over it (000 §3).
  struct Mirror;
  std::vector<std::unique_ptr<Mirror>> mirrors_;
  double in_plane_ = 0;
  bool mirror_culling_ = true;
  /// Refraction (000 §4): the facets, the chains through them, and what an image needs.
  struct Refracting;
  std::unique_ptr<const Refracting> refracting_;
  void add_refracted(const Vec3& x, const Vec3& n, LocalPassResult& result) const;
  /// Gathers the images of one path at x into result.refracted.
  void gather_refracted(const Refracting& r, const RefractionPath& path, const Vec3& x,
                        const Vec3& n, LocalPassResult& result) const;
  /// Glossy transfer (003). Null without glossy surfaces lit by something.
  std::unique_ptr<const GlossyTransfer> glossy_;
  /// Point lights, decided exactly (localpass/point_light_visibility.h). Null without any.
  std::unique_ptr<const PointLightVisibility> lights_;
};

}  // namespace rad
