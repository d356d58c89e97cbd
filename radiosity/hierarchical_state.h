#pragma once
/// The hierarchical solver's state and steps, shared by its two source files:
/// hierarchical_solver.cpp (the links, the sweeps, the result) and hierarchical_refinement.cpp
/// (splitting leaves). Internal to radiosity/: callers use solve_hierarchical()
/// (radiosity/hierarchical_solver.h).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "radiosity/error_bound.h"
#include "radiosity/hierarchical_solver.h"
#include "radiosity/mesher.h"
#include "radiosity/parallel_parts.h"
#include "radiosity/patch_clusters.h"
#include "radiosity/patch_mesh.h"
#include "radiosity/random_stream.h"
#include "radiosity/refinement_limit.h"
#include "radiosity/shooter.h"
#include "radiosity/solver.h"

namespace rad {

/// A source is linked whole when its size is below kOpening times its distance from the
/// receiver (the opening angle of Barnes and Hut's tree codes): the 1 / r^2 and the cosines
/// then change by some per cent across it. Measured on the Cornell box without refinement
/// (docs/algorithms.md): RMS error at the accuracy points 6.6% at 0.5, 4.8% at 0.25, 3.9% at
/// 0.1 (the progressive solver's, unrefined: 3.9%), for 0.7, 2.0 and 3.7 million links.
inline constexpr double kOpening = 0.25;
/// The opening test: a source of this size (a diameter) is small beside a gap this wide.
inline bool small_beside(double size, double gap) { return gap > 0 && size < kOpening * gap; }
/// A leaf takes a source that has pieces (a patch, a split element) whole, as one polygon of
/// its mean radiosity with its exact form factor at the leaf's centroid, beyond this many
/// bounding radii of it; nearer, piece by piece (HierarchicalSolver::needs_pieces). Nearer
/// than about 7 radii the pieces a leaf sees most are not the ones the rest of the scene sees
/// most, and the mean takes light out of the system: measured on the closed cube under a point
/// light (the test AClosedRoomAbsorbsAllOfAPointLightsPower), the walls absorb 1.6% less than
/// the light delivers (blue, rho 0.8) at 3 radii (the progressive solver's near field), 0.36%
/// less at 5, 0.003% at 7 and 0.1% more at 9 (link_patches' opening test, the rule before);
/// on the Cornell box 7 makes 10.6 million links against 13.9 at 9, 6.1 at 3, for the same
/// error at the accuracy points (docs/algorithms.md).
inline constexpr double kSourceRadii = 7;
inline bool in_source_near_field(const Vec3& x, const Sphere& source) {
  return (x - source.centre).norm() < kSourceRadii * source.radius;
}
/// What the hidden sources that refinement stops measuring again may bring a leaf together,
/// as a fraction of its refinement limit (drop_faint_hidden). Measured at the accuracy points:
/// the largest error 1.90% on the Cornell box and 0.81% in the room at 0 (every source
/// measured again), 1.89% and 0.80% at 0.5; a furnished room solves 1.26 times faster
/// (docs/algorithms.md).
inline constexpr double kFaintHidden = 0.5;
/// Linking leaves a cluster or a patch out when what it may bring (its reach) is within this
/// fraction of the receiver's budget, and leaves out at most the budget in all
/// (HierarchicalSolver::settle).
inline constexpr double kDeferredPieces = 8;
/// H += factor B(source): a patch (patch links) or an element as the source (element links:
/// element `source`, or patch -1 - source where a patch's links were handed down). The factor
/// is grey: the solver carries no filters and no mirrors (hierarchical_unsupported()), so a
/// visible form factor is the same in every channel. A float holds it to 1e-7 of itself, and
/// makes a link 8 bytes (a building's hundred million links at default settings fit in 1 GB).
struct SourceLink {
  int source;
  float factor;
  SourceLink(int s, const Rgb& f) : source(s), factor(static_cast<float>(f[0])) {}
};
/// H += sum over bins of weight_b x flux_b(cluster).
struct ClusterLink {
  int cluster;
  std::array<float, kBins> weight;
};

class HierarchicalSolver {
 public:
  HierarchicalSolver(const RayCaster& caster, const SolverSettings& settings,
                     const std::function<void(const SolveProgress&)>& progress)
      : caster_(caster),
        scene_(caster.scene()),
        settings_(settings),
        diagonal_(scene_.bounds().diagonal()),
        epsilon_(1e-5 * diagonal_),
        in_plane_(scene_.tolerance().in_plane),
        rays_(caster, settings, epsilon_),
        progress_(progress) {
    solution_.settings = settings;
    solution_.patches = make_patches(scene_, settings.patch_size * diagonal_, [&](double done) {
      report(SolveProgress::Stage::meshing, done);
    });
    solution_.elements = make_elements(solution_.patches, settings.element_levels);
    const size_t patch_count = solution_.patches.size();
    centroid_.resize(patch_count);
    radius_.resize(patch_count);
    for (size_t p = 0; p < patch_count; ++p) {
      double area;
      element_geometry(solution_.patches[p].corners, &area, &centroid_[p]);
      radius_[p] = bounding_sphere(solution_.patches[p].corners, centroid_[p]).radius;
    }
    find_leaves();
    patch_roots_.resize(patch_count);
    for (size_t e = 0; e < solution_.elements.size(); ++e) {
      if (solution_.elements[e].parent < 0)
        patch_roots_[solution_.elements[e].patch].push_back(static_cast<int>(e));
    }
    clusters_.emplace(solution_.patches, centroid_);
  }

  void link() {
    const size_t count = solution_.patches.size();
    patch_links_.resize(count);
    cluster_links_.resize(count);
    deferred_.resize(count);
    handed_.assign(count, 0);
    element_links_.resize(solution_.elements.size());
    element_cluster_links_.resize(solution_.elements.size());
    element_blocked_.resize(solution_.elements.size());
    patch_blocked_.resize(count);
    // What linking may leave out is judged by the light each leaf starts with: its emission
    // and what it reflects of the point lights.
    direct_.assign(solution_.elements.size(), Rgb::Zero());
    tbb::parallel_for(size_t(0), leaves_.size(), [&](size_t k) { light(leaves_[k]); });
    std::vector<Rgb> first_light(solution_.elements.size(), Rgb::Zero());
    for (const int e : leaves_)
      first_light[e] = emission(e) + reflectance(e).cwiseProduct(direct_[e]);
    find_brightest(first_light);
    for_in_parts(count, 0, 1, reporter(SolveProgress::Stage::linking),
                 [&](size_t p) { link_patch(static_cast<int>(p)); });
    count_links();
    // The links' row sums: the gather of a uniform radiosity of 1. The exact form factors of a
    // point sum to at most 1 (to the hemisphere); the clusters' and the centroids' estimates
    // can pass it, and a row that does is scaled back to 1, so that no element takes in more
    // than all it sees (the sweeps converge, and the bound below holds with sigma < 1).
    radiosity_.assign(solution_.elements.size(), Rgb::Ones());
    pull();
    unit_flux_.resize(clusters_->size());
    for (int c = 0; c < clusters_->size(); ++c) unit_flux_[c] = clusters_->flux(c);
    patch_row_.resize(count);
    for (size_t p = 0; p < count; ++p) patch_row_[p] = patch_row(static_cast<int>(p));
    row_scale_.assign(solution_.elements.size(), 1.0);
    for (const int e : leaves_) row_scale_[e] = scale_of(e);
    // The initial state: every live leaf radiates its emission.
    for (const int e : leaves_) radiosity_[e] = emission(e);
    for (const int e : leaves_) emitted_ += radiosity_[e] * solution_.elements[e].area;
    emitted_ += scene_.light_power();
  }

  /// Opens, for each patch, the clusters and patches its linking left out (deferred_) where
  /// the leaves' radiosity now makes them pass its budget (Hanrahan, Salzman and Aupperle's
  /// BF refinement: a link is refined where its form factor times its source's radiosity is
  /// large, and the radiosity is known only as the solution proceeds). Returns the number
  /// opened; the sweeps are to go on when it is not 0.
  int open_deferred();

  /// Patch p's links' row sum: their gather of a uniform radiosity of 1.
  Rgb patch_row(int p) const {
    Rgb h = Rgb::Zero();
    for (const SourceLink& l : patch_links_[p]) h += Rgb::Constant(l.factor);
    for (const ClusterLink& l : cluster_links_[p]) h += taken(l, unit_flux_[l.cluster]);
    return h;
  }
  void count_links() {
    links_ = 0;
    for (size_t p = 0; p < patch_links_.size(); ++p)
      links_ += static_cast<long long>(patch_links_[p].size() + cluster_links_[p].size());
    for (size_t e = 0; e < element_links_.size(); ++e)
      links_ += static_cast<long long>(element_links_[e].size() + element_cluster_links_[e].size());
  }

  /// Leaf e's row sum (its patch's links' and its own, at a uniform radiosity of 1), and the
  /// scale that brings it down to 1 where it passes 1.
  Rgb row_sum(int e) const {
    Rgb h = patch_row_[solution_.elements[e].patch];
    for (const SourceLink& l : element_links_[e]) h += Rgb::Constant(l.factor);
    for (const ClusterLink& l : element_cluster_links_[e]) h += taken(l, unit_flux_[l.cluster]);
    return h;
  }
  double scale_of(int e) const {
    const double sum = row_sum(e).maxCoeff();
    return sum > 1 ? 1 / sum : 1.0;
  }

  /// Splits the leaves whose radiosity misses the plane through their mesh neighbours' by
  /// more than the refinement limit (the progressive solver's refine_by_neighbours: Gouraud
  /// display and the local pass take a plane well, not what it misses: shadow edges, corners).
  /// Each new leaf takes its parent's radiosity and patch links, and measures its own links
  /// to the sources its parent linked to element by element. Returns the number split.
  int refine();

  void iterate() {
    std::vector<Element>& elements = solution_.elements;
    const double emitted = emitted_.sum();
    converged_ = false;
    std::vector<Rgb> next(elements.size(), Rgb::Zero()), irradiance(elements.size(), Rgb::Zero());
    std::vector<Rgb> patch_irradiance(solution_.patches.size(), Rgb::Zero());
    for (int sweep = 0; sweep < std::max(1, settings_.max_shots); ++sweep) {
      pull();
      tbb::parallel_for(size_t(0), solution_.patches.size(), [&](size_t p) {
        patch_irradiance[p] = gather_at_patch(static_cast<int>(p));
      });
      tbb::parallel_for(size_t(0), leaves_.size(), [&](size_t k) {
        const int e = leaves_[k];
        Rgb h = patch_irradiance[elements[e].patch];
        for (const SourceLink& l : element_links_[e])
          h += static_cast<double>(l.factor) * source_radiosity(l.source);
        for (const ClusterLink& l : element_cluster_links_[e])
          h += taken(l, clusters_->flux(l.cluster));
        h *= row_scale_[e];
        h += direct_[e];
        irradiance[e] = h;
        next[e] = emission(e) + reflectance(e).cwiseProduct(h);
      });
      // The change, in index order (the same sum for any thread count).
      change_ = Rgb::Zero();
      largest_change_ = Rgb::Zero();
      for (const int e : leaves_) {
        const Rgb d = next[e] - radiosity_[e];
        change_ += d.cwiseAbs() * elements[e].area;
        largest_change_ = largest_change_.cwiseMax(d.cwiseAbs());
        radiosity_[e] = next[e];
      }
      ++sweeps_;
      const double fraction = emitted > 0 ? change_.cwiseAbs().sum() / emitted : 0;
      if (progress_) {
        SolveProgress now;
        now.stage = SolveProgress::Stage::shooting;
        now.shots = sweeps_;
        now.unshot_fraction = fraction;
        now.target_fraction = settings_.unshot_fraction;
        now.elements = static_cast<int>(leaves_.size());
        progress_(now);
      }
      // (Not on the first sweep after a refinement: it moves the new leaves, whose area is
      // small, and their neighbours have not taken it in yet.)
      if (fraction < settings_.unshot_fraction && (sweep > 0 || refined_ == 0)) {
        converged_ = true;
        break;
      }
    }
    irradiance_ = std::move(irradiance);
  }

  Solution finish(double seconds) {
    std::vector<Element>& elements = solution_.elements;
    SolveStats& stats = solution_.stats;
    for (Patch& p : solution_.patches) p.radiosity = Rgb::Zero();
    int leaf_count = 0;
    for (size_t e = 0; e < elements.size(); ++e) {
      if (!elements[e].is_leaf()) continue;
      ++leaf_count;
      elements[e].radiosity = emission(static_cast<int>(e));  // buried: as solve() leaves them
    }
    Rgb absorbed = Rgb::Zero();
    for (const int e : leaves_) {
      Element& el = elements[e];
      el.radiosity = radiosity_[e];
      el.irradiance = irradiance_.empty() ? Rgb::Zero() : irradiance_[e];
      absorbed += (Rgb::Ones() - reflectance(e)).cwiseProduct(el.irradiance) * el.area;
    }
    for (const Element& el : elements) {
      if (!el.is_leaf()) continue;
      Patch& p = solution_.patches[el.patch];
      p.radiosity += el.radiosity * (el.area / p.area);
    }
    for (Patch& p : solution_.patches) p.shot = p.radiosity;
    stats.shots = sweeps_;
    stats.refined = refined_;
    stats.patches = static_cast<int>(solution_.patches.size());
    stats.elements = leaf_count;
    stats.seconds = seconds;
    stats.emitted = emitted_;
    stats.absorbed = absorbed;
    stats.unshot = change_;
    stats.escaped = emitted_ - absorbed - change_;
    stats.unshot_fraction = emitted_.sum() > 0 ? change_.cwiseAbs().sum() / emitted_.sum() : 0;
    stats.converged = converged_;
    stats.links = links_;
    const Shooter::PairCounts counted = rays_.counts();
    stats.visibility_pairs = counted.pairs;
    stats.unhidden_pairs = counted.unhidden;
    stats.hidden_pairs = counted.hidden;
    stats.error_bound = error_bound();
    find_brightest(radiosity_);
    for (size_t p = 0; p < deferred_.size(); ++p) {
      double reaches = 0;
      for (const int entry : deferred_[p]) reaches += reach(static_cast<int>(p), entry);
      stats.left_out += static_cast<long long>(deferred_[p].size());
      stats.left_out_bound = std::max(stats.left_out_bound, reaches);
    }
    return std::move(solution_);
  }

 private:
  void report(SolveProgress::Stage stage, double done) const {
    if (!progress_) return;
    SolveProgress r;
    r.stage = stage;
    r.stage_done = done;
    progress_(r);
  }
  std::function<void(double)> reporter(SolveProgress::Stage stage) const {
    return [this, stage](double done) { report(stage, done); };
  }
  const Material& material(int polygon) const {
    return scene_.materials[scene_.polygons[polygon].material];
  }
  Rgb emission(int e) const { return material(solution_.elements[e].polygon).emission; }
  /// The point lights' irradiance at point x of element e (0 with no lights).
  Rgb lights_at(int e, const Vec3& x) const {
    if (scene_.lights.empty()) return Rgb::Zero();
    return rays_.point_light_irradiance(x, solution_.patches[solution_.elements[e].patch].normal);
  }
  /// Leaf e's direct light from the point lights, at its centroid: their one shot (a light has
  /// no area, so it is no link's source; the progressive solver shoots them once, first). What
  /// reaches no leaf escapes in the ledger, as there.
  void light(int e) { direct_[e] = lights_at(e, solution_.elements[e].centroid); }
  Rgb reflectance(int e) const { return material(solution_.elements[e].polygon).reflectance; }

  /// The live leaves (not buried inside a closed object, as solve() finds them) of each patch,
  /// and each patch's live area.
  void find_leaves() {
    const std::vector<Element>& elements = solution_.elements;
    std::vector<char>& buried = buried_;
    buried.assign(elements.size(), 0);
    tbb::parallel_for(size_t(0), elements.size(), [&](size_t e) {
      const Element& el = elements[e];
      if (el.is_leaf())
        buried[e] = rays_.is_buried(el.centroid, solution_.patches[el.patch].normal);
    });
    patch_leaves_.resize(solution_.patches.size());
    live_area_.assign(solution_.patches.size(), 0.0);
    for (size_t e = 0; e < elements.size(); ++e) {
      if (!elements[e].is_leaf() || buried[e]) continue;
      leaves_.push_back(static_cast<int>(e));
      patch_leaves_[elements[e].patch].push_back(static_cast<int>(e));
      live_area_[elements[e].patch] += elements[e].area;
    }
  }

  /// Each patch's radiosity (the area mean of its live leaves), and each cluster's flux per bin
  /// (sum over its patches of B A_live max(0, +-n_i)), children before parents.
  void pull() {
    // A split element a link names (made before the split) shows the area mean of its live
    // children; children come after their parents in the list.
    const std::vector<Element>& elements = solution_.elements;
    live_below_.assign(elements.size(), 0.0);
    for (size_t e = elements.size(); e-- > 0;) {
      const Element& el = elements[e];
      if (el.is_leaf()) {
        live_below_[e] = buried_[e] ? 0.0 : el.area;
        continue;
      }
      Rgb sum = Rgb::Zero();
      for (int c = el.first_child; c < el.first_child + 4; ++c) {
        live_below_[e] += live_below_[c];
        sum += radiosity_[c] * live_below_[c];
      }
      radiosity_[e] = live_below_[e] > 0 ? Rgb(sum / live_below_[e]) : Rgb::Zero();
    }
    patch_radiosity_.assign(solution_.patches.size(), Rgb::Zero());
    for (size_t p = 0; p < patch_leaves_.size(); ++p) {
      if (!(live_area_[p] > 0)) continue;
      Rgb sum = Rgb::Zero();
      for (const int e : patch_leaves_[p]) sum += radiosity_[e] * solution_.elements[e].area;
      patch_radiosity_[p] = sum / live_area_[p];
    }
    clusters_->pull(patch_radiosity_, live_area_);
  }

  Rgb gather_at_patch(int p) const {
    Rgb h = Rgb::Zero();
    for (const SourceLink& l : patch_links_[p])
      h += static_cast<double>(l.factor) * patch_radiosity_[l.source];
    for (const ClusterLink& l : cluster_links_[p]) h += taken(l, clusters_->flux(l.cluster));
    return h;
  }
  /// What a cluster link takes of the cluster's flux.
  static Rgb taken(const ClusterLink& l, const FluxBins& flux) {
    Rgb h = Rgb::Zero();
    for (int b = 0; b < kBins; ++b) h += static_cast<double>(l.weight[b]) * flux[b];
    return h;
  }
  /// The weights, at point x of normal n, of a link to cluster `index` that its shadow rays
  /// found open: per bin, bin_weights(w) cos / (pi r^2), w the unit vector from the cluster's
  /// centre to x, r their distance, cos the receiver's (all 0 behind it).
  std::array<float, kBins> cluster_weights(int index, const Vec3& x, const Vec3& n) const {
    std::array<float, kBins> weight{};
    Vec3 w = x - (*clusters_)[index].centre;
    const double r = w.norm();
    if (!(r > 0)) return weight;
    w /= r;
    const double cos_receiver = -n.dot(w);
    if (!(cos_receiver > 0)) return weight;
    const std::array<double, kBins> bins = bin_weights(w);
    const double scale = cos_receiver / (std::numbers::pi * r * r);
    for (int b = 0; b < kBins; ++b) {  // (a float holds any weight of a cluster far away)
      weight[b] = static_cast<float>(
          std::min(bins[b] * scale, static_cast<double>(std::numeric_limits<float>::max())));
    }
    return weight;
  }

  /// Relinks each leaf's element links whose source has pieces (a split element, a patch) to
  /// the pieces where the leaf needs them (needs_pieces()): a receiver at a junction sees the
  /// near part of the surface it meets, not its mean (Hanrahan, Salzman and Aupperle 1991
  /// refine the source or the receiver of a link, whichever is larger). Then counts the links
  /// afresh.
  void open_sources();
  bool link_down(int e, const SourceLink& link, std::vector<SourceLink>& out);
  /// Leaf e takes a source with pieces (a patch, a split element) piece by piece where e lies
  /// in its near field (in_source_near_field()), or where its pieces' radiosities spread so
  /// far that taking it as uniform could cost e more than NearField::limit_share of its
  /// refinement limit (as the progressive solver's receivers take a shooter,
  /// radiosity/near_field.h). Elsewhere e takes the source's exact form factor at its
  /// centroid, at its mean radiosity.
  bool needs_pieces(int e, const Sphere& source, double area, const std::vector<int>& pieces) const;
  void link_or_hide(int e, int source, uint64_t key);
  /// Drops from leaf e's hidden sources the faintest, as long as all it drops would bring e
  /// at most kFaintHidden times its refinement limit if e saw them whole (Lambert's factor
  /// at e's centroid, times rho and the source's radiosity): a piece of e that sees some of
  /// them gains less than the refinement looks for. The rest are measured again by e's
  /// children and at its corners, where most are hidden still: in a furnished room, dropping
  /// them spared a quarter of all the pairs measured (shelves hide walls). Once per element:
  /// its children drop again against their own limits.
  void drop_faint_hidden(int e, double reference);

  /// What leaf e's own links (its element links and, once its patch's were handed down, its
  /// cluster links) give at point x of it: x its centroid (`corner` -1: the links' stored
  /// factors) or its corner `corner` (measured now, its hidden sources too).
  Rgb own_gather(int e, const Vec3& x, int corner) const;

  /// An element link's source: element s, or patch -1 - s (a patch link handed down).
  const Rgb& source_radiosity(int s) const {
    return s >= 0 ? radiosity_[s] : patch_radiosity_[-1 - s];
  }
  Patch source_patch(int s) const {
    return s >= 0 ? solution_.element_as_patch(s) : solution_.patches[-1 - s];
  }

  /// The height above patch p's plane of the farthest corner of `box`.
  double highest_above(const Eigen::AlignedBox3d& box, int p) const {
    const Patch& s = solution_.patches[p];
    double h = -s.normal.dot(s.corners[0]);
    for (int i = 0; i < 3; ++i)
      h += std::max(s.normal[i] * box.min()[i], s.normal[i] * box.max()[i]);
    return h;
  }
  /// Some corner of patch a in front of patch b's plane (beyond the scene's tolerance).
  bool in_front(int a, int b) const {
    const Patch& pa = solution_.patches[a];
    const Patch& pb = solution_.patches[b];
    return std::any_of(pa.corners.begin(), pa.corners.end(),
                       [&](const Vec3& c) { return pb.normal.dot(c - pb.corners[0]) > in_plane_; });
  }

  /// Patches p and q may see each other: distinct polygons, each in front of the other.
  bool may_see(int p, int q) const {
    if (p == q || solution_.patches[p].polygon == solution_.patches[q].polygon)
      return false;  // a planar polygon does not see itself
    return in_front(p, q) && in_front(q, p);
  }
  /// Links patch p to what it sees: down the cluster tree from the root, a cluster small beside
  /// its distance whose shadow rays agree is linked whole, a larger one is opened, and a leaf
  /// cluster's patches are linked by link_patches; a cluster or patch too faint to be worth
  /// opening is left out (deferred_), as long as all p leaves out stays within its budget
  /// (hierarchical_linking.cpp).
  void link_patch(int p);
  /// What may hide a cluster or a patch from a receiver patch whole: the points of it that
  /// gather through its links, and the polygons that enclose it, the last that hid something
  /// first.
  struct Blocker {
    int polygon;
    Vec3 normal;  ///< The polygon's, turned to the gathering points: they lie in front
    double offset;
  };
  struct Blockers {
    std::vector<Vec3> from;
    std::vector<Blocker> polygons;
  };
  /// Patch p's Blockers: its leaves' centroids (anywhere on it where refinement may split
  /// them), and the polygons rays from its centroid meet first in 26 directions (to a cube's
  /// faces, edges and corners: a room's floor, ceiling and walls).
  Blockers enclosing(int p) const;
  /// True when one of `blockers` hides the hull of the points `to` (a cluster's box, a patch;
  /// `box` bounds them) from every point that gathers (Shooter::hides_between): every shadow ray
  /// would be blocked, so what is inside brings exactly nothing, and is neither linked, nor opened,
  /// nor left out. Without it a storey's receivers open the clusters of the storeys above and
  /// below down to their patches, which the slabs hide (bench/results/building_profile.md).
  bool hidden_whole(std::span<const Vec3> to, const Eigen::AlignedBox3d& box,
                    Blockers& blockers) const;
  /// link_patch's walk down from the clusters on `stack`.
  void link_from(int p, std::vector<int>& stack, Blockers& blockers);
  /// Opens a deferred_ entry for patch p: a cluster's children go on `stack` (a leaf
  /// cluster's patches are linked), a patch is linked.
  void open(int p, int entry, std::vector<int>& stack, Blockers& blockers);
  /// What a deferred_ entry (cluster `entry`, or patch -1 - entry) may bring patch p at most:
  /// its brightest leaf's radiosity times sphere_form_factor_bound from p to its bounding
  /// sphere ((r / d)^2 for a sphere of radius r at distance d from p's nearest point, less
  /// low over p's horizon; 1 where they meet), an upper bound on the exact form factor of
  /// anything inside it, hidden or not.
  /// Irradiance, not reflected light: a black receiver's absorption counts in the ledger (with
  /// rho, a black sky's links were left out and its light counted as escaped). Largest channel.
  double reach(int p, int entry) const;
  /// Leaves `entry` out of p's links (deferred_) when its reach is within a kDeferredPieces-th
  /// of p's budget.
  bool defer(int p, int entry);
  /// Opens p's brightest deferred entries until the reach of the rest is within its budget;
  /// returns the number opened.
  int settle(int p);
  /// The brightest leaf radiosity of each patch and each cluster (per channel).
  void find_brightest(const std::vector<Rgb>& radiosity);
  /// Hands each patch's links down to its leaves (refine()): each leaf measures the patch's
  /// links at its own centroid and weighs its cluster links there.
  void hand_down(const std::vector<int>& patches);
  /// Links patch p to cluster `index` whole when a few shadow rays agree (all pass or all are
  /// blocked); false when they disagree and the cluster is to be opened.
  bool link_cluster(int p, int index);
  /// Links patch p to patch q: at p's centroid when both are small beside their distance, else
  /// each live leaf of p to each of q's.
  void link_patches(int p, int q);

  /// The certified bound on the sweeps' own error, from the last sweep's change r: the sweeps
  /// are Jacobi's, B' = E + R F B with F the links' (scaled) gather, so B* - B' = R F (B* - B)
  /// and |B* - B'| <= sigma |r| / (1 - sigma), sigma = max over leaves of rho_e x its row sum
  /// (per channel): the gather of a uniform radiosity of 1. It covers the sweeps, not what the
  /// links approximate.
  Rgb error_bound() const {
    Rgb sigma = Rgb::Zero();
    for (const int e : leaves_)
      sigma = sigma.cwiseMax(reflectance(e).cwiseProduct(row_sum(e) * row_scale_[e]));
    Rgb bound;
    for (int c = 0; c < 3; ++c) {
      bound[c] = sigma[c] < 1 ? sigma[c] * largest_change_[c] / (1 - sigma[c])
                              : std::numeric_limits<double>::infinity();
    }
    return bound;
  }

  const RayCaster& caster_;
  const Scene& scene_;
  const SolverSettings settings_;
  const double diagonal_;
  const double epsilon_;
  const double in_plane_;  ///< The scene's tolerance (a call to tolerance() bounds the scene)
  const Shooter rays_;
  const std::function<void(const SolveProgress&)>& progress_;
  Solution solution_;
  std::vector<Vec3> centroid_;
  std::vector<double> radius_;
  std::vector<int> leaves_;
  std::vector<std::vector<int>> patch_leaves_;
  std::vector<std::vector<int>> patch_roots_;  ///< Per patch: its top-level elements
  std::vector<double> live_area_;
  std::optional<PatchClusters> clusters_;
  std::vector<std::vector<SourceLink>> patch_links_;
  std::vector<std::vector<ClusterLink>> cluster_links_;
  std::vector<std::vector<SourceLink>> element_links_;
  /// Per element: the cluster links its patch handed down, weighed at its centroid.
  std::vector<std::vector<ClusterLink>> element_cluster_links_;
  /// Per patch: the clusters (index) and patches (-1 - index) its linking left out, too
  /// faint to open; together they may bring it at most defer_budget_ (what unshot light may
  /// bring a leaf: --unshot times B_ref).
  std::vector<std::vector<int>> deferred_;
  const double reference_ = reference_radiosity(scene_);  ///< B_ref
  const double defer_budget_ = settings_.faint_share * settings_.unshot_fraction * reference_;
  std::vector<Rgb> patch_brightest_, cluster_brightest_;  ///< find_brightest()'s
  std::vector<char> handed_;         ///< Per patch: its links were handed down to its leaves
  std::vector<FluxBins> unit_flux_;  ///< Per cluster: its flux at a uniform radiosity of 1
  /// Where refinement may follow: the sources (as element links name them) and the patches
  /// that a link found hidden at its receiver's centroid. A piece of the receiver may see them
  /// (a leaf in a penumbra whose parent's centroid was in the umbra), so each new leaf measures
  /// them again, and the contact corner test measures them at the corners.
  const bool keep_blocked_ = settings_.refine_threshold > 0 && settings_.refine_passes > 0;
  std::vector<std::vector<int>> element_blocked_, patch_blocked_;
  /// Per element: its faint hidden sources were dropped (once: each level drops at most
  /// kFaintHidden times its own limit).
  std::vector<char> faint_dropped_;
  std::vector<Rgb> radiosity_, patch_radiosity_, irradiance_;
  std::vector<Rgb> direct_;         ///< Per leaf: the point lights' irradiance (light())
  std::vector<double> row_scale_;   ///< Per leaf: 1, or what brings its row sum down to 1
  std::vector<Rgb> patch_row_;      ///< Per patch: its links' row sum (their gather of 1)
  std::vector<char> buried_;        ///< Per element: inside a closed object (leaves only)
  std::vector<double> live_below_;  ///< pull()'s: per element, the live area of its leaves
  Rgb emitted_ = Rgb::Zero(), change_ = Rgb::Zero(), largest_change_ = Rgb::Zero();
  int sweeps_ = 0, refined_ = 0;
  bool converged_ = false;
  long long links_ = 0;
};

}  // namespace rad
