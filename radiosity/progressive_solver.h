#pragma once
/// The progressive solver's state and steps, shared by its two source files: solver.cpp
/// (meshing, shooting, the ledger) and refinement.cpp (splitting elements, re-gathering).
/// Internal to radiosity/: callers use solve() (radiosity/solver.h).
#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "radiosity/form_factor_store.h"
#include "radiosity/mesher.h"
#include "radiosity/near_field.h"
#include "radiosity/random_stream.h"
#include "radiosity/receiver_culling.h"
#include "radiosity/refinement_limit.h"
#include "radiosity/shooter.h"
#include "radiosity/solution.h"
#include "radiosity/solver.h"
#include "scene/ray_caster.h"

namespace rad {

/// The state of one solve and its steps. Every parallel step writes per-element slots; every
/// sum is taken in a fixed order (serially in index order, or over fixed blocks added in block
/// order), so results do not depend on the thread count.
class ProgressiveSolver {
 public:
  /// Meshes the scene (telling `progress` how far it is: SolveProgress::Stage) and sets the
  /// initial state.
  ProgressiveSolver(const RayCaster& caster, const SolverSettings& settings,
                    const std::function<void(const SolveProgress&)>& progress = {});

  /// Shoots until the unshot power is below the target (or the shot limit).
  void shoot_until_converged(const std::function<void(const SolveProgress&)>& progress);

  /// Refinement on the accumulated solution (cf. Cohen et al. 1986): an element is split when
  /// its radiosity differs by more than the refinement limit from the plane fitted through its
  /// mesh neighbours' radiosities (least squares over their centroids). Gouraud display
  /// reproduces linear variation, so only what a plane misses (shadow edges, corners, also
  /// those cast by indirect light that no single shot shows) is refined. Children re-gather.
  /// Returns the number of elements split.
  int refine_by_neighbours();

  /// Patch radiosities, the ledger's unshot term and the display ambient term.
  Solution finish(double seconds);

 private:
  std::vector<Patch>& patches() { return solution_.patches; }
  std::vector<Element>& elements() { return solution_.elements; }
  SolveStats& stats() { return solution_.stats; }
  const Material& material(int polygon) const {
    return scene_.materials[scene_.polygons[polygon].material];
  }
  /// The part of the light arriving at a polygon's front that stays with it (reflected or
  /// absorbed): a filter passes the rest on, and a mirror reflects it specularly; it is
  /// received where it lands (shadow rays carry the transmittance, mirror images the specular
  /// reflectance), so the ledger counts it there.
  Rgb stays(int polygon) const {
    const Material& m = material(polygon);
    // (A mirror's specular part goes on too: its images deliver it. A glossy surface's leaves
    // the solution: redirects.)
    const bool passes_on = scene_.mirror_depth > 0 || m.is_glossy_mirror();
    return Rgb::Ones() - m.transmittance - (passes_on ? m.specular : Rgb::Zero());
  }
  /// The part of the light arriving at a polygon's front that a glossy mirror reflects into
  /// its lobe: the ledger's "redirected", which the solution does not carry (paper 003). (A
  /// roughened pane reaches the solver as a filter: solve() in solver.cpp.)
  Rgb redirects(int polygon) const {
    const Material& m = material(polygon);
    return m.is_glossy_mirror() ? m.specular : Rgb::Zero();
  }
  /// A filter's back neither reflects nor emits (one-sided, DESIGN §3) but absorbs what it does
  /// not pass on: the ledger asks its elements what reaches their backs too. Opaque polygons'
  /// backs stay unasked (in a closed scene nothing reaches them; in an open one, what does is
  /// counted as escaped).
  bool absorbs_at_back(int polygon) const { return material(polygon).is_filter(); }
  Rgb back_ff(const Element& el, const Patch& source, uint64_t key) const {
    return rays_.visible_form_factor(el.centroid, -solution_.patches[el.patch].normal, el.polygon,
                                     source, key);
  }
  // A re-gather can leave a patch's unshot radiosity slightly negative (its children hold a
  // little less than their parent did: the patch has over-shot). Negative unshot radiosity is
  // shot like positive, as a correction, so the remaining power is measured in absolute value.
  double unshot_power(int p) const {
    return solution_.patches[p].unshot.cwiseAbs().sum() * live_area_[p];
  }

  /// Where a polygon passes through or under a closed object (a floor under a block standing
  /// on it), its patches are partly buried: that part receives nothing and is hidden from
  /// everything. A patch's unshot radiosity is therefore a density over its live area A_live
  /// (power = Delta B A_live): shot over the whole patch, a receiver's shadow rays to the
  /// buried part are blocked, so it gets Delta B FF V with V ~ A_live / A, what the live part
  /// alone sends. Spread over the whole area instead, Delta B would be diluted by A_live / A
  /// and the light of every patch along a contact line lost in part, the floor's most of all.
  /// A_live is measured on an 8 x 8 grid of each patch; elements are buried when their
  /// centroid is, and buried elements neither receive nor split.
  void find_buried(const std::function<void(double)>& progress);

  bool refinement_enabled() const { return settings_.refine_threshold > 0 && reference_ > 0; }
  /// The refinement limit at an element (radiosity/refinement_limit.h).
  double limit(double local_radiosity, bool near_contact) const {
    return refinement_limit(settings_.refine_threshold, reference_, local_radiosity, near_contact);
  }
  /// Not buried and longer than the smallest element (the test runs for every candidate of
  /// every shot, so the length is taken once, when the element is made).
  bool splittable(int e) const { return !buried_[e] && long_enough_[e]; }
  void split_into(int e, std::vector<int>& children);
  Rgb visible_ff(const Element& el, const Patch& source, uint64_t key, int fewer = 1) const {
    return rays_.visible_form_factor(el.centroid, solution_.patches[el.patch].normal, el.polygon,
                                     source, key, fewer);
  }
  /// Elements near a concave junction or a contact (another polygon's front within their
  /// size) are split by the constant-radiosity test (see refine_during_shot).
  bool near_a_contact(const Element& el) const {
    return rays_.faces_within(el.centroid, solution_.patches[el.patch].normal,
                              longest_edge(el.corners));
  }

  /// The visible form factor from element e to a node of a patch's tree, for the near field:
  /// the node as a patch of its own, with a quarter of the shadow rays.
  Rgb piece_form_factor(int e, int node, int shot) const {
    return visible_ff(solution_.elements[e], solution_.element_as_patch(node),
                      stream_key(shot, e, StreamKind::near, node), 2);
  }
  /// Whether receiver e gathers `patch` piece by piece: near it, or where its spread could
  /// make it off by more than the receiver tolerates (near_tolerance). Never a patch that is
  /// one leaf (--element-levels 0, not split): its one piece is the patch itself, which the
  /// far path measures with all the shadow rays and keeps in the budgeted store, as the density
  /// over its live area (find_buried); gathered as its leaf it had a quarter of the rays, the
  /// leaf's density diluted by A_live / A where the patch is partly buried, and a stored pair
  /// per receiver without a budget (9 million on the 15,000-polygon building).
  bool is_near(int e, int patch, double spread) const {
    if (near_field_.is_one_piece(solution_.elements, patch)) return false;
    return NearField::gathers_in_pieces(solution_.elements[e].centroid, patch_bounds_[patch],
                                        solution_.patches[patch].area, spread, near_tolerance(e));
  }
  /// The irradiance error receiver e tolerates from a piece taken as uniform: a share of the
  /// refinement limit at its radiosity (NearField::limit_share), through its reflectance.
  double near_tolerance(int e) const {
    const Element& el = solution_.elements[e];
    const double rho = material(el.polygon).reflectance.maxCoeff();
    if (!(rho > 0)) return std::numeric_limits<double>::infinity();
    return NearField::limit_share * limit(el.radiosity.cwiseAbs().maxCoeff(), near_contact_[e]) /
           rho;
  }

  /// One shot of patch `shooter`'s unshot radiosity to every leaf that can receive it.
  void shoot(int shooter);

  /// The leaves of the patches in receiver_patches_, in index order, into receivers_: a shot's
  /// receivers (the others get exactly nothing from it: radiosity/receiver_culling.h).
  void collect_receivers();

  /// Each receiver takes in this shot's irradiance (gathered in pieces when it is near the
  /// shooter, else `far` x its form factor; at a filter's back delta x back_ff_) in parallel.
  /// The sums do not depend on the thread count: the power kept and absorbed over fixed blocks
  /// of leaves added in block order, each patch's unshot radiosity serially in element order
  /// from what the parallel part left per leaf. (Serial whole, with a pass of its own for the
  /// far receivers' irradiance, this was a tenth of the solve's wall time.) Returns the power
  /// the receivers keep, plus what glossy ones redirect.
  Rgb distribute(const Rgb& delta, const Rgb& far);

  /// One leaf's part of distribute(): its radiosity and irradiance, and what it adds to the
  /// power kept and absorbed. Returns its patch and the unshot radiosity it adds there (patch
  /// -1: it receives nothing).
  std::pair<int, Rgb> take_in(int e, const Rgb& delta, const Rgb& far, Rgb& kept, Rgb& absorbed,
                              Rgb& redirected);

  /// This shot's visible form factor at each of `which`. A pair's form factor does not change
  /// between shots: a patch shooting again reuses what its first shot measured (same value,
  /// same jitter), so repeated shots cast no rays. The store is kept while it fits in
  /// form_factor_budget bytes; beyond that, patches measure afresh each time.
  void receive(const std::vector<int>& which, int shooter, int shot);

  /// receive() at one leaf.
  void receive_at(int e, int shooter, int shot);

  /// The visible form factor from element e to patch `shooter`: stored, or measured now (and
  /// stored when there is room).
  Rgb stored_form_factor(int shooter, int e, uint64_t key);

  /// Splits leaves where linear interpolation from the corners misses this shot's radiosity
  /// at the centre by more than the limit; children receive the shot and re-gather. Near a
  /// contact or a concave edge (near_a_contact), where points of the local pass see an element
  /// from close by and at a large solid angle, the test is stricter: any corner off the centre
  /// by more than the limit splits, because the local pass takes an element's radiosity as
  /// constant over it, and a linear rise across it is what a point beside it sees.
  void refine_during_shot(int shooter, const Rgb& delta, int shot);

  /// The point lights' one shot (scene/point_lights.h), in the constructor.
  void shoot_point_lights();

  /// A new child re-gathers everything shot so far (and the point lights' direct light), H = sum_j
  /// S_j FF(x, patch j), with S_j the radiosity patch j has shot. The form factor of a pair does
  /// not change between shots, so this is exactly what the child would hold had it existed from the
  /// start; inheriting the parent's value instead would mix form factors taken at two points, which
  /// can sum to more than 1 (the furnace then overshoots). The change in received power goes
  /// through the ledger: absorbed, the owning patch's unshot radiosity, and escaped.
  void regather(const std::vector<int>& children);

  const Scene& scene_;
  const SolverSettings settings_;
  const double diagonal_;
  const double reference_;
  const double min_size_;
  const double contact_size_;  ///< Elements near contacts no smaller than this by the constant test
  Solution solution_;
  const Shooter rays_;
  std::vector<Sphere> patch_bounds_;
  std::vector<double> live_area_;   ///< Per patch: its area outside closed objects
  std::vector<char> buried_;        ///< Per element: its centroid is inside a closed object
  std::vector<char> long_enough_;   ///< Per element: longer than the smallest element
  std::vector<char> near_contact_;  ///< Per element: another polygon's front is near
  /// Per element, radiosity received and not yet shot, and shot so far (meaningful on leaves;
  /// a patch's unshot radiosity is their mean over its live area), and what it shoots now.
  std::vector<Rgb> leaf_unshot_, leaf_shot_, shooting_;
  /// The spread (NearField::average_up) of the shooter and its nodes as they shoot now, and of
  /// every patch and node as what they have shot so far (for re-gathers).
  double shooting_spread_ = 0;
  std::vector<float> shooting_node_spread_, shot_node_spread_;
  std::vector<double> shot_spread_;
  NearField near_field_{0, {}};
  FormFactorStore store_{size_t(1) << 30};     ///< 1 GiB
  std::vector<Rgb> near_incoming_;             ///< This shot's irradiance at the near receivers
  std::vector<std::pair<int, Rgb>> to_patch_;  ///< distribute()'s per-leaf shares of unshot
  std::vector<char> near_;  ///< This shot: the element is in the shooter's near field
  std::vector<int> leaves_;
  std::vector<double> power_;  ///< Per patch, its unshot power (shoot_until_converged's scratch)
  std::optional<ReceiverCulling> culling_;     ///< Made with the patches
  std::vector<int> receiver_patches_;          ///< This shot's: the patches that can receive it...
  std::vector<int> receivers_;                 ///< ...and their leaves, in index order
  std::vector<char> receiving_;                ///< Per patch: in receiver_patches_ (a scratch)
  std::vector<std::vector<int>> leaf_blocks_;  ///< collect_receivers()'s, per block of leaves
  std::vector<Rgb> ff_;               ///< This shot's visible form factor per element, per channel.
  std::vector<Rgb> back_ff_;          ///< The same at the backs of filters' elements...
  std::vector<Rgb> back_irradiance_;  ///< ...and what has reached those backs so far.
};

}  // namespace rad
