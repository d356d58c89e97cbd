#include "radiosity/solver.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <tuple>

#include "geometry/lambert.h"
#include "radiosity/form_factor_store.h"
#include "radiosity/mesher.h"
#include "radiosity/near_field.h"
#include "radiosity/patch_mesh.h"
#include "radiosity/random_stream.h"
#include "radiosity/shooter.h"

namespace rad {
double reference_radiosity(const Scene& scene) {
  const double area = scene.total_area();
  Rgb rho_area = Rgb::Zero();
  for (const Polygon& p : scene.polygons)
    rho_area += scene.materials[p.material].reflectance * p.area;
  const Rgb power = scene.emitted_power();
  double reference = 0;
  for (int c = 0; c < 3; ++c) {
    reference = std::max(reference, power[c] / area / (1 - rho_area[c] / area));
  }
  return reference;
}

namespace {

/// The state of one solve and its steps. Every parallel step writes per-element slots; every
/// sum is taken serially in index order, so results do not depend on the thread count.
class ProgressiveSolver {
 public:
  ProgressiveSolver(const RayCaster& caster, const SolverSettings& settings)
      : scene_(caster.scene()),
        settings_(settings),
        diagonal_(scene_.bounds().diagonal()),
        reference_(reference_radiosity(scene_)),
        min_size_(settings.min_element_size * diagonal_),
        contact_size_(std::max(min_size_, settings.patch_size * diagonal_ / 16)),
        rays_(caster, settings, 1e-5 * diagonal_) {  // offsets ~100x float precision
    solution_.settings = settings;
    solution_.patches = make_patches(scene_, settings.patch_size * diagonal_);
    solution_.elements = make_elements(solution_.patches, settings.element_levels);
    find_buried();
    // Initial state: each patch's unshot radiosity and each element's radiosity is its emission.
    for (size_t i = 0; i < patches().size(); ++i) {
      Patch& p = patches()[i];
      p.unshot = material(p.polygon).emission;
      p.radiosity = p.unshot;
      stats().emitted += p.unshot * live_area_[i];
      double area;
      Vec3 centroid;
      element_geometry(p.corners, &area, &centroid);
      patch_bounds_.push_back(bounding_sphere(p.corners, centroid));
    }
    for (Element& e : elements()) e.radiosity = material(e.polygon).emission;
    near_field_ = NearField(patches().size(), elements());
    shot_spread_.assign(patches().size(), 0.0);
    leaf_unshot_.resize(elements().size());
    leaf_shot_.assign(elements().size(), Rgb::Zero());
    shooting_.assign(elements().size(), Rgb::Zero());
    for (size_t e = 0; e < elements().size(); ++e)
      leaf_unshot_[e] = buried_[e] ? Rgb::Zero() : material(elements()[e].polygon).emission;
    leaves_ = solution_.leaves();
  }

  /// Shoots until the unshot power is below the target (or the shot limit).
  void shoot_until_converged(const std::function<void(const SolveProgress&)>& progress) {
    const double emitted = stats().emitted.sum();
    while (true) {
      int shooter = -1;
      double largest = 0, remaining = 0;
      for (size_t p = 0; p < patches().size(); ++p) {
        const double power = unshot_power(static_cast<int>(p));
        remaining += power;
        if (power > largest) largest = power, shooter = static_cast<int>(p);  // ties: lowest index
      }
      stats().unshot_fraction = emitted > 0 ? remaining / emitted : 0;
      stats().converged = shooter < 0 || stats().unshot_fraction <= settings_.unshot_fraction;
      if (stats().converged || stats().shots >= settings_.max_shots) return;
      shoot(shooter);
      if (progress) {
        SolveProgress report;
        report.shots = stats().shots;
        report.target_fraction = settings_.unshot_fraction;
        report.elements = static_cast<int>(leaves_.size());
        double after = 0;
        for (size_t p = 0; p < patches().size(); ++p) after += unshot_power(static_cast<int>(p));
        report.unshot_fraction = emitted > 0 ? after / emitted : 0;
        progress(report);
      }
    }
  }

  /// Refinement on the accumulated solution (cf. Cohen et al. 1986): an element is split when
  /// its radiosity differs by more than the refinement limit from the plane fitted through its
  /// mesh neighbours' radiosities (least squares over their centroids). Gouraud display
  /// reproduces linear variation, so only what a plane misses (shadow edges, corners, also
  /// those cast by indirect light that no single shot shows) is refined. Children re-gather.
  /// Returns the number of elements split.
  int refine_by_neighbours() {
    if (!refinement_enabled()) return 0;
    const ElementMesh mesh(solution_, scene_.tolerance().pad);
    std::vector<char> split(mesh.face_count(), 0);
    tbb::parallel_for(0, mesh.face_count(), [&](int f) {
      const Element& el = solution_.elements[mesh.element(f)];
      if (!splittable(mesh.element(f))) return;
      const std::optional<Rgb> fitted = mesh.neighbour_plane_at(solution_, f);
      if (!fitted) return;
      const Rgb& predicted = *fitted;
      const double miss = (el.radiosity - predicted).cwiseAbs().maxCoeff();
      split[f] =
          miss > limit(el.radiosity.cwiseMax(predicted).maxCoeff(), near_contact_[mesh.element(f)]);
    });
    std::vector<int> children;
    for (int f = 0; f < mesh.face_count(); ++f) {
      if (split[f]) split_into(mesh.element(f), children);
    }
    if (children.empty()) return 0;
    regather(children);
    leaves_ = solution_.leaves();
    return static_cast<int>(children.size() / 4);
  }

  /// Patch radiosities, the ledger's unshot term and the display ambient term.
  Solution finish(double seconds) {
    Rgb area_rho = Rgb::Zero();
    double total_area = 0;
    for (Patch& p : patches()) p.radiosity = Rgb::Zero();
    for (const int e : leaves_) {
      const Element& el = elements()[e];
      patches()[el.patch].radiosity += el.radiosity * (el.area / patches()[el.patch].area);
    }
    for (size_t i = 0; i < patches().size(); ++i) {
      const Patch& p = patches()[i];
      stats().unshot += p.unshot * live_area_[i];
      area_rho += material(p.polygon).reflectance * p.area;
      total_area += p.area;
    }
    // Cohen et al. 1988: the unshot power spread over the scene and multiplied out by the
    // interreflection factor R = 1 / (1 - mean rho). Display only, never in the values.
    for (int c = 0; c < 3; ++c) {
      solution_.ambient[c] = stats().unshot[c] / total_area / (1 - area_rho[c] / total_area);
    }
    stats().patches = static_cast<int>(patches().size());
    stats().elements = static_cast<int>(leaves_.size());
    stats().seconds = seconds;
    std::tie(stats().visibility_pairs, stats().unhidden_pairs) = rays_.counts();
    return std::move(solution_);
  }

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
    // (A mirror's specular part goes on too: its images deliver it.)
    return Rgb::Ones() - m.transmittance - (scene_.mirror_depth > 0 ? m.specular : Rgb::Zero());
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
  void find_buried() {
    buried_.assign(elements().size(), 0);
    long_enough_.assign(elements().size(), 0);
    near_contact_.assign(elements().size(), 0);
    tbb::parallel_for(size_t(0), elements().size(), [&](size_t e) {
      const Element& el = elements()[e];
      buried_[e] = rays_.is_buried(el.centroid, solution_.patches[el.patch].normal);
      long_enough_[e] = longest_edge(el.corners) > min_size_;
      near_contact_[e] = near_a_contact(el);
    });
    constexpr int grid = 8;
    live_area_.assign(patches().size(), 0);
    tbb::parallel_for(size_t(0), patches().size(), [&](size_t i) {
      const Patch& p = patches()[i];
      int live = 0;
      for (int a = 0; a < grid; ++a) {
        for (int b = 0; b < grid; ++b)
          live += !rays_.is_buried(patch_point(p, (a + 0.5) / grid, (b + 0.5) / grid), p.normal);
      }
      // Wholly buried: nothing of it is ever received, so nothing is shot; keep A.
      live_area_[i] = live > 0 ? p.area * live / (grid * grid) : p.area;
    });
  }

  bool refinement_enabled() const { return settings_.refine_threshold > 0 && reference_ > 0; }
  /// Errors are seen relative to the local brightness: the limit follows the local radiosity,
  /// clamped to [floor, 1] x B_ref so that dark regions are resolved but black ones are not
  /// chased forever. The floor is dark_floor in general: a dark element is seen at a small
  /// solid angle from the brighter points around it, and its error is small beside theirs. Near
  /// a contact or a concave edge (`near_contact`) it is contact_dark_floor: a point of the local
  /// pass beside the edge sees the elements next to it at half its hemisphere, and in a contact
  /// shadow it is as dark as they are, so what it tolerates is relative to that darkness, not
  /// to the scene's mean.
  double limit(double local_radiosity, bool near_contact) const {
    const double floor = near_contact ? contact_dark_floor : dark_floor;
    return settings_.refine_threshold * std::clamp(local_radiosity, floor * reference_, reference_);
  }
  static constexpr double dark_floor = 0.1;
  /// Measured on the Cornell box (bench/results/global_accuracy.md, point 10: the floor 2 mm
  /// from the short block's front, in its umbra, where blue is a twentieth of red): path-traced,
  /// the blue radiosity of the block's face falls by 40% over its lowest 3 mm and the floor's
  /// by a quarter over its first 4 mm. Held to 0.1 x B_ref, the elements there stayed 4.7 mm
  /// and constant across that fall, the lowest rows too bright on both sides (+2.6% at the
  /// point in blue); at 0.02 they follow it (+1.4%), for 5% more elements. 0.05 reaches +1.9%;
  /// 0.01 goes no further than 0.02.
  static constexpr double contact_dark_floor = 0.02;
  /// Not buried and longer than the smallest element (the test runs for every candidate of
  /// every shot, so the length is taken once, when the element is made).
  bool splittable(int e) const { return !buried_[e] && long_enough_[e]; }
  void split_into(int e, std::vector<int>& children) {
    split_element(elements(), e);
    const int first = elements()[e].first_child;
    back_irradiance_.resize(elements().size(), Rgb::Zero());
    buried_.resize(elements().size(), 0);
    leaf_unshot_.resize(elements().size(), Rgb::Zero());
    leaf_shot_.resize(elements().size(), Rgb::Zero());
    shooting_.resize(elements().size(), Rgb::Zero());
    shooting_node_spread_.resize(elements().size(), 0.0f);
    shot_node_spread_.resize(elements().size(), 0.0f);
    for (int c = 0; c < 4; ++c) {
      children.push_back(first + c);
      // The same density over each part: what the element held, shot and is to shoot.
      leaf_unshot_[first + c] = leaf_unshot_[e];
      leaf_shot_[first + c] = leaf_shot_[e];
      shooting_[first + c] = shooting_[e];
      back_irradiance_[first + c] = back_irradiance_[e];  // inherited, as the front's is
      const Element& child = elements()[first + c];
      buried_[first + c] = rays_.is_buried(child.centroid, solution_.patches[child.patch].normal);
      long_enough_.resize(elements().size(), 0);
      long_enough_[first + c] = longest_edge(child.corners) > min_size_;
      near_contact_.resize(elements().size(), 0);
      near_contact_[first + c] = near_a_contact(child);
    }
    ++stats().refined;
  }
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
    const Element& piece = solution_.elements[node];
    Patch part;
    part.polygon = piece.polygon;
    part.corners = piece.corners;
    part.normal = solution_.patches[piece.patch].normal;
    part.area = piece.area;
    return visible_ff(solution_.elements[e], part, stream_key(shot, e, StreamKind::near, node), 2);
  }
  /// Whether receiver e gathers `patch` piece by piece: near it, or where its spread could
  /// make it off by more than the receiver tolerates (near_tolerance).
  bool is_near(int e, int patch, double spread) const {
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

  /// One shot of patch `shooter`'s unshot radiosity to every leaf.
  void shoot(int shooter) {
    Patch& source = patches()[shooter];
    const Rgb delta = source.unshot;
    source.unshot = Rgb::Zero();
    const int shot = stats().shots;
    // The pieces the near field is shot from, with what each has not shot yet.
    near_field_.for_each_leaf(elements(), shooter, [&](int l) {
      shooting_[l] = leaf_unshot_[l];
      leaf_shot_[l] += leaf_unshot_[l];
      leaf_unshot_[l] = Rgb::Zero();
    });
    shooting_spread_ =
        near_field_.average_up(elements(), shooter, shooting_, shooting_node_spread_, buried_);
    // What the shooter has shot so far, for re-gathers: only its leaves changed. (A split
    // leaves a tree's means and spreads as they were: children hold their parent's value.)
    shot_spread_[shooter] =
        near_field_.average_up(elements(), shooter, leaf_shot_, shot_node_spread_, buried_);

    // Receive at every leaf's centroid; split where this shot is far from linear.
    back_irradiance_.resize(elements().size(), Rgb::Zero());
    far_density_ = delta;
    receive(leaves_, shooter, shot);
    // The far receivers see the shooter with the radiosity that keeps the shot's energy.
    far_density_ = near_field_.far_density(elements(), shooter, leaves_, near_, ff_,
                                           live_area_[shooter], shooting_, delta);
    for (const int e : leaves_) {
      if (!near_[e] && !buried_[e]) incoming_[e] = far_density_.cwiseProduct(ff_[e]);
    }
    if (refinement_enabled()) refine_during_shot(shooter, delta, shot);

    // Distribute, serially in element order (deterministic sums).
    Rgb received = Rgb::Zero();
    for (const int e : leaves_) {
      if (incoming_[e] == Rgb::Zero() && back_ff_[e] == Rgb::Zero()) continue;
      Element& el = elements()[e];
      const Rgb rho = material(el.polygon).reflectance;
      const Rgb irradiance = incoming_[e];
      const Rgb reflected = rho.cwiseProduct(irradiance);
      const Rgb stay = stays(el.polygon).cwiseProduct(irradiance);
      el.radiosity += reflected;
      el.irradiance += irradiance;
      received += stay * el.area;
      stats().absorbed += (stay - reflected) * el.area;
      if (absorbs_at_back(el.polygon)) {
        const Rgb back = delta.cwiseProduct(back_ff_[e]);
        const Rgb absorbed = stays(el.polygon).cwiseProduct(back) * el.area;
        back_irradiance_[e] += back;
        received += absorbed;
        stats().absorbed += absorbed;
      }
      Patch& owner = patches()[el.patch];
      owner.unshot += reflected * (el.area / live_area_[el.patch]);
      leaf_unshot_[e] += reflected;
    }
    stats().escaped += delta * live_area_[shooter] - received;
    source.shot += delta;
    ++stats().shots;
  }

  /// This shot's visible form factor at each of `which`. A pair's form factor does not change
  /// between shots: a patch shooting again reuses what its first shot measured (same value,
  /// same jitter), so repeated shots cast no rays. The store is kept while it fits in
  /// form_factor_budget bytes; beyond that, patches measure afresh each time.
  void receive(const std::vector<int>& which, int shooter, int shot) {
    store_.grow(shooter, patches().size(), elements().size());
    near_field_.grow(elements());
    ff_.resize(elements().size(), Rgb::Zero());
    incoming_.resize(elements().size(), Rgb::Zero());
    back_ff_.resize(elements().size(), Rgb::Zero());
    near_.resize(elements().size(), 0);
    // Small fixed chunks: a few receivers (those near the shooter, those measured for the
    // first time) cost far more than the rest, and sit together in element order.
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, which.size(), 16),
        [&](const tbb::blocked_range<size_t>& range) {
          for (size_t k = range.begin(); k != range.end(); ++k) receive_at(which[k], shooter, shot);
        },
        tbb::simple_partitioner());
  }

  /// receive() at one leaf.
  void receive_at(int e, int shooter, int shot) {
    if (buried_[e]) return;  // stays zero
    ff_[e] = stored_form_factor(shooter, e, stream_key(shot, e, StreamKind::centre, 0));
    near_[e] = is_near(e, shooter, shooting_spread_);
    if (near_[e]) {
      incoming_[e] = near_field_.gather(
          elements(), e, shooter, shooting_, shooting_node_spread_, near_tolerance(e),
          [&](int node) { return piece_form_factor(e, node, shot); }, true);
    } else {
      incoming_[e] = far_density_.cwiseProduct(ff_[e]);
    }
    if (absorbs_at_back(elements()[e].polygon)) {
      back_ff_[e] = back_ff(elements()[e], solution_.patches[shooter],
                            stream_key(shot, e, StreamKind::back, 0));
    }
  }

  /// The visible form factor from element e to patch `shooter`: stored, or measured now (and
  /// stored when there is room).
  Rgb stored_form_factor(int shooter, int e, uint64_t key) {
    Rgb ff;
    if (store_.find(shooter, e, &ff)) return ff;
    ff = visible_ff(elements()[e], solution_.patches[shooter], key);
    store_.put(shooter, e, ff);
    return ff;
  }

  /// Splits leaves where linear interpolation from the corners misses this shot's radiosity
  /// at the centre by more than the limit; children receive the shot and re-gather. Near a
  /// contact or a concave edge (near_a_contact), where points of the local pass see an element
  /// from close by and at a large solid angle, the test is stricter: any corner off the centre
  /// by more than the limit splits, because the local pass takes an element's radiosity as
  /// constant over it, and a linear rise across it is what a point beside it sees.
  void refine_during_shot(int shooter, const Rgb& delta, int shot) {
    const Patch& source = patches()[shooter];
    const Sphere& sb = patch_bounds_[shooter];
    std::vector<int> candidates = leaves_;
    bool any_split = false;
    while (!candidates.empty()) {
      std::vector<char> split(candidates.size(), 0);
      tbb::parallel_for(size_t(0), candidates.size(), [&](size_t k) {
        const int e = candidates[k];
        const Element& el = elements()[e];
        const Rgb rho = material(el.polygon).reflectance;
        const double scale = rho.maxCoeff() * delta.cwiseAbs().maxCoeff();
        const double lim = limit(
            (el.radiosity + rho.cwiseProduct(delta).cwiseProduct(ff_[e])).cwiseAbs().maxCoeff(),
            near_contact_[e]);
        if (scale <= lim || !splittable(e)) return;
        // Largest possible form factor from this element to the shooter (bounding spheres):
        // skip pairs that cannot reach the limit.
        const Sphere eb{el.centroid, near_field_.radius(e)};
        const double gap = (eb.centre - sb.centre).norm() - eb.radius - sb.radius;
        const double ff_max = form_factor_bound(source.area, gap);
        if (scale * ff_max <= lim) return;
        // Corners pulled 0.1% towards the centre so no point lies on a neighbouring polygon.
        // Near a contact, down to a sixteenth of the patch size (the patch size stays the one
        // knob of the mesh's resolution: coarse patches do not refine every concave edge to
        // the smallest element).
        const bool constant_test = near_contact_[e] && longest_edge(el.corners) > contact_size_;
        double off = 0;
        Rgb mean = Rgb::Zero();
        for (size_t c = 0; c < el.corners.size(); ++c) {
          const Vec3 x = el.corners[c] + 1e-3 * (el.centroid - el.corners[c]);
          const Rgb at_corner = rays_.visible_form_factor(
              x, solution_.patches[el.patch].normal, el.polygon, source,
              stream_key(shot, e, StreamKind::corner, static_cast<int>(c)));
          if (constant_test) {
            off = std::max(off, (ff_[e] - at_corner).cwiseAbs().maxCoeff());
          } else {
            mean += at_corner;
          }
        }
        if (!constant_test)
          off = (ff_[e] - mean / static_cast<double>(el.corners.size())).cwiseAbs().maxCoeff();
        split[k] = scale * off > lim;
      });
      std::vector<int> children;
      for (size_t k = 0; k < candidates.size(); ++k) {
        if (split[k]) split_into(candidates[k], children);
      }
      if (children.empty()) break;
      any_split = true;
      ff_.resize(elements().size(), Rgb::Zero());
      back_ff_.resize(elements().size(), Rgb::Zero());
      receive(children, shooter, shot);
      regather(children);
      candidates = std::move(children);
    }
    if (any_split) leaves_ = solution_.leaves();
  }

  /// A new child re-gathers everything shot so far, H = sum_j S_j FF(x, patch j), with S_j the
  /// radiosity patch j has shot. The form factor of a pair does not change between shots, so
  /// this is exactly what the child would hold had it existed from the start; inheriting the
  /// parent's value instead would mix form factors taken at two points, which can sum to more
  /// than 1 (the furnace then overshoots). The change in received power goes through the
  /// ledger: absorbed, the owning patch's unshot radiosity, and escaped.
  void regather(const std::vector<int>& children) {
    const int shot = stats().shots;
    std::vector<Rgb> gathered(children.size(), Rgb::Zero()), back(children.size(), Rgb::Zero());
    for (size_t j = 0; j < patches().size(); ++j) {
      if (patches()[j].shot != Rgb::Zero())
        store_.grow(static_cast<int>(j), patches().size(), elements().size());
    }
    near_field_.grow(elements());
    tbb::parallel_for(size_t(0), children.size(), [&](size_t k) {
      const Element& el = elements()[children[k]];
      if (buried_[children[k]]) return;  // receives nothing
      const bool at_back = absorbs_at_back(el.polygon);
      for (size_t j = 0; j < solution_.patches.size(); ++j) {
        const Patch& p = solution_.patches[j];
        if (p.shot == Rgb::Zero()) continue;
        if (is_near(children[k], static_cast<int>(j), shot_spread_[j])) {
          const int e = children[k];
          gathered[k] += near_field_.gather(
              elements(), e, static_cast<int>(j), leaf_shot_, shot_node_spread_, near_tolerance(e),
              [&](int node) { return piece_form_factor(e, node, shot); }, false);
        } else {
          gathered[k] += p.shot.cwiseProduct(stored_form_factor(
              static_cast<int>(j), children[k],
              stream_key(shot, children[k], StreamKind::regather, static_cast<int>(j))));
        }
        if (at_back) {
          back[k] += p.shot.cwiseProduct(back_ff(
              el, p, stream_key(shot, children[k], StreamKind::back, static_cast<int>(j) + 1)));
        }
      }
    });
    for (size_t k = 0; k < children.size(); ++k) {
      Element& el = elements()[children[k]];
      const Rgb rho = material(el.polygon).reflectance;
      const Rgb power = (gathered[k] - el.irradiance) * el.area;  // against what it inherited
      el.irradiance = gathered[k];
      el.radiosity = material(el.polygon).emission + rho.cwiseProduct(gathered[k]);
      stats().absorbed += (stays(el.polygon) - rho).cwiseProduct(power);
      stats().escaped -= stays(el.polygon).cwiseProduct(power);
      if (absorbs_at_back(el.polygon)) {
        const Rgb back_power =
            stays(el.polygon).cwiseProduct(back[k] - back_irradiance_[children[k]]) * el.area;
        back_irradiance_[children[k]] = back[k];
        stats().absorbed += back_power;
        stats().escaped -= back_power;
      }
      Patch& owner = patches()[el.patch];
      owner.unshot += rho.cwiseProduct(power) / live_area_[el.patch];
      leaf_unshot_[children[k]] += rho.cwiseProduct(power) / el.area;
    }
  }

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
  FormFactorStore store_{size_t(1) << 30};  ///< 1 GiB
  std::vector<Rgb> incoming_;               ///< This shot's irradiance per element
  Rgb far_density_ = Rgb::Zero();           ///< The shooter's radiosity as far receivers see it
  std::vector<char> near_;  ///< This shot: the element is in the shooter's near field
  std::vector<int> leaves_;
  std::vector<Rgb> ff_;               ///< This shot's visible form factor per element, per channel.
  std::vector<Rgb> back_ff_;          ///< The same at the backs of filters' elements...
  std::vector<Rgb> back_irradiance_;  ///< ...and what has reached those backs so far.
};

}  // namespace

Solution solve(const RayCaster& caster, const SolverSettings& settings,
               const std::function<void(const SolveProgress&)>& progress) {
  settings.validate();
  const auto start = std::chrono::steady_clock::now();
  ProgressiveSolver solver(caster, settings);
  solver.shoot_until_converged(progress);
  for (int pass = 0; pass < settings.refine_passes; ++pass) {
    if (solver.refine_by_neighbours() == 0) break;
    solver.shoot_until_converged(progress);
  }
  return solver.finish(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace rad
