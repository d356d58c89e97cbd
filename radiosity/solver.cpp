#include "radiosity/solver.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <utility>

#include "geometry/lambert.h"
#include "radiosity/error_bound.h"
#include "radiosity/hierarchical_solver.h"
#include "radiosity/mesher.h"
#include "radiosity/parallel_parts.h"
#include "radiosity/progressive_solver.h"

namespace rad {
double reference_radiosity(const Scene& scene) {
  const double area = scene.total_area();
  Rgb rho_area = Rgb::Zero();
  for (const Polygon& p : scene.polygons)
    rho_area += scene.materials[p.material].reflectance * p.area;
  const Rgb power = scene.emitted_power() + scene.light_power();
  double reference = 0;
  for (int c = 0; c < 3; ++c) {
    reference = std::max(reference, power[c] / area / (1 - rho_area[c] / area));
  }
  return reference;
}

MeshNeeds least_mesh_needs(const Scene& scene, const SolverSettings& settings) {
  const double per_patch = std::pow(4.0, settings.element_levels);
  MeshNeeds needs;
  needs.elements =
      least_patches(scene, settings.patch_size * scene.bounds().diagonal()) * per_patch;
  // The element with a triangle's corners, and ProgressiveSolver's seven Rgb per element
  // (leaf_unshot_, leaf_shot_, shooting_, ff_, back_ff_, near_incoming_, back_irradiance_).
  constexpr double kBytes = sizeof(Element) + 3 * sizeof(Vec3) + 7 * sizeof(Rgb);
  needs.bytes = needs.elements * kBytes;
  return needs;
}

ProgressiveSolver::ProgressiveSolver(const RayCaster& caster, const SolverSettings& settings,
                                     const std::function<void(const SolveProgress&)>& progress)
    : scene_(caster.scene()),
      settings_(settings),
      diagonal_(scene_.bounds().diagonal()),
      reference_(reference_radiosity(scene_)),
      min_size_(settings.min_element_size * diagonal_),
      contact_size_(std::max(min_size_, settings.patch_size * diagonal_ / 16)),
      rays_(caster, settings, 1e-5 * diagonal_) {  // offsets ~100x float precision
  solution_.settings = settings;
  const auto stage = [&](SolveProgress::Stage what) {
    return [&progress, what](double done) {
      if (!progress) return;
      SolveProgress report;
      report.stage = what;
      report.stage_done = done;
      progress(report);
    };
  };
  solution_.patches =
      make_patches(scene_, settings.patch_size * diagonal_, stage(SolveProgress::Stage::meshing));
  solution_.elements = make_elements(solution_.patches, settings.element_levels);
  find_buried(stage(SolveProgress::Stage::burying));
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
  std::vector<char> receives_at_back(patches().size());
  for (size_t i = 0; i < patches().size(); ++i)
    receives_at_back[i] = absorbs_at_back(patches()[i].polygon);
  culling_.emplace(patches(), std::move(receives_at_back), scene_.tolerance().in_plane,
                   !rays_.sees_images());
  shot_spread_.assign(patches().size(), 0.0);
  leaf_unshot_.resize(elements().size());
  leaf_shot_.assign(elements().size(), Rgb::Zero());
  shooting_.assign(elements().size(), Rgb::Zero());
  for (size_t e = 0; e < elements().size(); ++e)
    leaf_unshot_[e] = buried_[e] ? Rgb::Zero() : material(elements()[e].polygon).emission;
  leaves_ = solution_.leaves();
  if (!scene_.lights.empty()) shoot_point_lights();
}

void ProgressiveSolver::shoot_point_lights() {
  // The lights shoot once, first: each leaf takes in their direct light at its centroid (as
  // from a patch's shot), and reflects it on as unshot radiosity. A light has no area, so it
  // never shoots again (new children re-gather it: regather). The ledger: what reaches no
  // element (past the scene, the backs of opaque polygons, mirrors' specular part, refracting
  // objects) escapes.
  const Rgb power = scene_.light_power();
  stats().emitted += power;
  std::vector<Rgb> front(elements().size(), Rgb::Zero()), back(elements().size(), Rgb::Zero());
  tbb::parallel_for(size_t(0), leaves_.size(), [&](size_t k) {
    const int e = leaves_[k];
    if (buried_[e]) return;
    const Element& el = elements()[e];
    const Vec3& n = solution_.patches[el.patch].normal;
    front[e] = rays_.point_light_irradiance(el.centroid, n);
    if (absorbs_at_back(el.polygon)) back[e] = rays_.point_light_irradiance(el.centroid, -n);
  });
  back_irradiance_.resize(elements().size(), Rgb::Zero());
  Rgb kept = Rgb::Zero();
  for (const int e : leaves_) {  // in index order: the sums do not depend on the threads
    Element& el = elements()[e];
    const Rgb rho = material(el.polygon).reflectance;
    const Rgb stay = stays(el.polygon);
    const Rgb reflected = rho.cwiseProduct(front[e]);
    el.irradiance += front[e];
    el.radiosity += reflected;
    leaf_unshot_[e] += reflected;
    patches()[el.patch].unshot += reflected * (el.area / live_area_[el.patch]);
    stats().absorbed += (stay - rho).cwiseProduct(front[e]) * el.area;
    kept += stay.cwiseProduct(front[e]) * el.area;
    back_irradiance_[e] = back[e];
    stats().absorbed += stay.cwiseProduct(back[e]) * el.area;
    kept += stay.cwiseProduct(back[e]) * el.area;
    const Rgb redirected = redirects(el.polygon).cwiseProduct(front[e]) * el.area;
    stats().redirected += redirected;
    kept += redirected;
  }
  stats().escaped += power - kept;
}

void ProgressiveSolver::shoot_until_converged(
    const std::function<void(const SolveProgress&)>& progress) {
  const double emitted = stats().emitted.sum();
  for (bool shot = false;; shot = true) {
    // Each patch's unshot power in parallel (a pass over every patch each shot: on the
    // building, 74,000 patches 30,000 times), then summed and searched serially in index order.
    power_.resize(patches().size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, power_.size(), 4096),
                      [&](const tbb::blocked_range<size_t>& range) {
                        for (size_t p = range.begin(); p != range.end(); ++p)
                          power_[p] = unshot_power(static_cast<int>(p));
                      });
    int shooter = -1;
    double largest = 0, remaining = 0;
    for (size_t p = 0; p < power_.size(); ++p) {
      remaining += power_[p];
      if (power_[p] > largest) largest = power_[p], shooter = static_cast<int>(p);  // ties: lowest
    }
    stats().unshot_fraction = emitted > 0 ? remaining / emitted : 0;
    if (progress && shot) {  // the state after the last shot
      SolveProgress report;
      report.shots = stats().shots;
      report.target_fraction = settings_.unshot_fraction;
      report.elements = static_cast<int>(leaves_.size());
      report.unshot_fraction = stats().unshot_fraction;
      progress(report);
    }
    stats().converged = shooter < 0 || stats().unshot_fraction <= settings_.unshot_fraction;
    if (stats().converged || stats().shots >= settings_.max_shots) return;
    shoot(shooter);
  }
}

Solution ProgressiveSolver::finish(double seconds) {
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
  // The iteration's error (radiosity/error_bound.h): every live leaf's unshot radiosity, against
  // the scene's largest reflectance. (A shooter is seen as a weighted mean of its leaves, so the
  // leaves' largest bounds what any receiver still has to get; buried leaves shoot nothing.)
  Rgb largest_unshot = Rgb::Zero(), largest_reflectance = Rgb::Zero();
  for (const int e : leaves_) {
    if (!buried_[e]) largest_unshot = largest_unshot.cwiseMax(leaf_unshot_[e].cwiseAbs());
  }
  for (const Material& m : scene_.materials)
    largest_reflectance = largest_reflectance.cwiseMax(m.reflectance);
  stats().error_bound = iteration_error_bound(largest_unshot, largest_reflectance);
  stats().patches = static_cast<int>(patches().size());
  stats().elements = static_cast<int>(leaves_.size());
  stats().seconds = seconds;
  const Shooter::PairCounts counted = rays_.counts();
  stats().visibility_pairs = counted.pairs;
  stats().unhidden_pairs = counted.unhidden;
  stats().hidden_pairs = counted.hidden;
  return std::move(solution_);
}

void ProgressiveSolver::find_buried(const std::function<void(double)>& progress) {
  const size_t count = elements().size();
  buried_.assign(count, 0);
  long_enough_.assign(count, 0);
  near_contact_.assign(count, 0);
  for_in_parts(
      count, 0, 1, progress,
      [&](size_t e) {
        const Element& el = elements()[e];
        buried_[e] = rays_.is_buried(el.centroid, solution_.patches[el.patch].normal);
        long_enough_[e] = longest_edge(el.corners) > min_size_;
        near_contact_[e] = near_a_contact(el);
      },
      4096);
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

void ProgressiveSolver::shoot(int shooter) {
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

  // Receive at the centroid of every leaf that can; split where this shot is far from linear.
  back_irradiance_.resize(elements().size(), Rgb::Zero());
  culling_->receivers(shooter, receiver_patches_);
  collect_receivers();
  receive(receivers_, shooter, shot);
  // The far receivers see the shooter with the radiosity that keeps the shot's energy.
  const Rgb far = near_field_.far_density(elements(), shooter, receivers_, near_, ff_,
                                          live_area_[shooter], shooting_, delta);
  if (refinement_enabled()) refine_during_shot(shooter, delta, shot);

  stats().escaped += delta * live_area_[shooter] - distribute(delta, far);
  source.shot += delta;
  ++stats().shots;
}

void ProgressiveSolver::collect_receivers() {
  receivers_.clear();
  // Where many patches receive (a room's shot reaches most of the room), one pass over the
  // leaves (kept in index order) picks theirs; where few do, their trees are walked and the
  // leaves sorted. Both give the same list. (The sort of every shot's leaves was 8% of the
  // Cornell box's solve, serial.)
  if (receiver_patches_.size() * 8 >= patches().size()) {
    receiving_.resize(patches().size(), 0);
    for (const int p : receiver_patches_) receiving_[p] = 1;
    // Fixed blocks of leaves in parallel, each into a list of its own, joined in block order.
    constexpr size_t block = 8192;
    leaf_blocks_.resize((leaves_.size() + block - 1) / block);
    tbb::parallel_for(size_t(0), leaf_blocks_.size(), [&](size_t b) {
      std::vector<int>& picked = leaf_blocks_[b];
      picked.clear();
      for (size_t k = b * block; k < std::min(leaves_.size(), (b + 1) * block); ++k) {
        if (receiving_[elements()[leaves_[k]].patch]) picked.push_back(leaves_[k]);
      }
    });
    for (const std::vector<int>& picked : leaf_blocks_)
      receivers_.insert(receivers_.end(), picked.begin(), picked.end());
    for (const int p : receiver_patches_) receiving_[p] = 0;
    return;
  }
  for (const int p : receiver_patches_)
    near_field_.for_each_leaf(elements(), p, [&](int leaf) { receivers_.push_back(leaf); });
  std::sort(receivers_.begin(), receivers_.end());
}

Rgb ProgressiveSolver::distribute(const Rgb& delta, const Rgb& far) {
  to_patch_.resize(receivers_.size());
  struct Sums {
    Rgb kept = Rgb::Zero(), absorbed = Rgb::Zero(), redirected = Rgb::Zero();
  };
  const Sums sums = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<size_t>(0, receivers_.size(), 512), Sums{},
      [&](const tbb::blocked_range<size_t>& range, Sums sum) {
        for (size_t k = range.begin(); k != range.end(); ++k)
          to_patch_[k] = take_in(receivers_[k], delta, far, sum.kept, sum.absorbed, sum.redirected);
        return sum;
      },
      [](const Sums& a, const Sums& b) {
        return Sums{a.kept + b.kept, a.absorbed + b.absorbed, a.redirected + b.redirected};
      });
  stats().absorbed += sums.absorbed;
  stats().redirected += sums.redirected;
  for (size_t k = 0; k < receivers_.size(); ++k) {
    if (to_patch_[k].first >= 0) patches()[to_patch_[k].first].unshot += to_patch_[k].second;
  }
  return sums.kept + sums.redirected;  // what the elements took in, or turned into lobes
}

std::pair<int, Rgb> ProgressiveSolver::take_in(int e, const Rgb& delta, const Rgb& far, Rgb& kept,
                                               Rgb& absorbed, Rgb& redirected) {
  if (buried_[e]) return {-1, Rgb::Zero()};
  Element& el = elements()[e];
  const Rgb irradiance = near_[e] ? near_incoming_[e] : far.cwiseProduct(ff_[e]);
  const bool at_back = absorbs_at_back(el.polygon);
  if (irradiance == Rgb::Zero() && !(at_back && back_ff_[e] != Rgb::Zero()))
    return {-1, Rgb::Zero()};
  const Rgb rho = material(el.polygon).reflectance;
  const Rgb reflected = rho.cwiseProduct(irradiance);
  const Rgb stay = stays(el.polygon).cwiseProduct(irradiance);
  el.radiosity += reflected;
  el.irradiance += irradiance;
  kept += stay * el.area;
  absorbed += (stay - reflected) * el.area;
  redirected += redirects(el.polygon).cwiseProduct(irradiance) * el.area;
  if (at_back) {
    const Rgb back = delta.cwiseProduct(back_ff_[e]);
    const Rgb taken = stays(el.polygon).cwiseProduct(back) * el.area;
    back_irradiance_[e] += back;
    kept += taken;
    absorbed += taken;
  }
  leaf_unshot_[e] += reflected;
  return {el.patch, reflected * (el.area / live_area_[el.patch])};
}

void ProgressiveSolver::receive(const std::vector<int>& which, int shooter, int shot) {
  store_.grow(shooter, patches().size(), which);
  near_field_.grow(elements());
  ff_.resize(elements().size(), Rgb::Zero());
  near_incoming_.resize(elements().size(), Rgb::Zero());
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

void ProgressiveSolver::receive_at(int e, int shooter, int shot) {
  if (buried_[e]) return;  // stays zero
  ff_[e] = stored_form_factor(shooter, e, stream_key(shot, e, StreamKind::centre, 0));
  near_[e] = is_near(e, shooter, shooting_spread_);
  if (near_[e]) {
    near_incoming_[e] = near_field_.gather(
        elements(), e, shooter, shooting_, shooting_node_spread_, near_tolerance(e),
        [&](int node) { return piece_form_factor(e, node, shot); }, true);
  }
  if (absorbs_at_back(elements()[e].polygon)) {
    back_ff_[e] = back_ff(elements()[e], solution_.patches[shooter],
                          stream_key(shot, e, StreamKind::back, 0));
  }
}

Rgb ProgressiveSolver::stored_form_factor(int shooter, int e, uint64_t key) {
  Rgb ff;
  if (store_.find(shooter, e, &ff)) return ff;
  ff = visible_ff(elements()[e], solution_.patches[shooter], key);
  store_.put(shooter, e, ff);
  return ff;
}

namespace {

/// The scene as the solver carries it: every roughened pane a plain filter of its glossy
/// transmittance, and with `glass`, every refracting interface a filter of what a crossing
/// passes (SolverSettings::glass_as_filters); nothing when that changes nothing.
std::optional<Scene> carried_scene(const Scene& scene, bool glass) {
  const auto changes = [&](const Material& m) {
    return m.is_glossy_pane() || (glass && m.refracts());
  };
  if (std::none_of(scene.materials.begin(), scene.materials.end(), changes)) return std::nullopt;
  Scene out = scene;
  for (Material& m : out.materials) {
    if (m.is_glossy_pane()) {
      m.transmittance = m.glossy_transmittance;
      m.glossy_transmittance = Rgb::Zero();
    } else if (glass && m.refracts()) {
      const Refraction& r = *m.refraction;
      const Rgb normal_reflection = ((r.ior.array() - 1) / (r.ior.array() + 1)).square().matrix();
      m.transmittance = r.fresnel ? Rgb(Rgb::Ones() - normal_reflection) : r.transmittance;
      m.refraction.reset();
    }
  }
  return out;
}

}  // namespace

Solution solve(const RayCaster& caster, const SolverSettings& settings,
               const std::function<void(const SolveProgress&)>& progress) {
  settings.validate();
  if (settings.method == SolverSettings::Method::hierarchical)
    return solve_hierarchical(caster, settings, progress);
  const auto start = std::chrono::steady_clock::now();
  // A roughened pane is carried as the filter of its glossy transmittance: at the scale of
  // patches its blur matters little, and a pane in front of a lamp would otherwise take most of
  // the scene's light out of the solution. Glass likewise, unbent (SolverSettings::
  // glass_as_filters). (Glossy mirrors are not carried: their chains of images cost too much on
  // a curved mesh; the ledger's `redirected` counts them.)
  const std::optional<Scene> carried = carried_scene(
      caster.scene(), settings.glass_as_filters && caster.scene().refraction_depth > 0);
  std::optional<RayCaster> carried_caster;
  if (carried) carried_caster.emplace(*carried);
  ProgressiveSolver solver(carried_caster ? *carried_caster : caster, settings, progress);
  solver.shoot_until_converged(progress);
  for (int pass = 0; pass < settings.refine_passes; ++pass) {
    if (solver.refine_by_neighbours() == 0) break;
    solver.shoot_until_converged(progress);
  }
  return solver.finish(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace rad
