#include "radiosity/solver.h"

#include <tbb/parallel_for.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>
#include <tuple>

#include "geometry/lambert.h"
#include "geometry/plane.h"
#include "radiosity/mesher.h"
#include "radiosity/patch_mesh.h"
#include "radiosity/random_stream.h"
#include "radiosity/shadow_culling.h"
#include "scene/error.h"
#include "scene/mirror_pieces.h"

namespace rad {
namespace {

/// A point of a patch at parametric (u, v) in [0, 1]^2: bilinear on quads; on triangles the
/// square is folded onto the triangle (area-preserving up to the fold).
Vec3 patch_point(const Patch& p, double u, double v) {
  const auto& c = p.corners;
  if (c.size() == 4)
    return (1 - u) * (1 - v) * c[0] + u * (1 - v) * c[1] + u * v * c[2] + (1 - u) * v * c[3];
  if (u + v > 1) u = 1 - u, v = 1 - v;
  return (1 - u - v) * c[0] + u * c[1] + v * c[2];
}

struct Sphere {
  Vec3 centre;
  double radius;
};
Sphere bounding_sphere(const std::vector<Vec3>& corners, const Vec3& centre) {
  double r = 0;
  for (const Vec3& c : corners) r = std::max(r, (c - centre).norm());
  return {centre, r};
}

/// True when p (in the piece's plane) lies in its outline (convex, counter-clockwise).
bool in_outline(const MirrorPiece& m, const Vec3& p) {
  const size_t k = m.outline.size();
  for (size_t i = 0; i < k; ++i) {
    const Vec3& a = m.outline[i];
    const Vec3& b = m.outline[(i + 1) % k];
    if ((b - a).cross(p - a).dot(m.normal) < 0) return false;
  }
  return true;
}

class Shooter {
 public:
  Shooter(const RayCaster& caster, const SolverSettings& settings, double epsilon)
      : caster_(caster),
        culling_(caster.scene(), epsilon),
        epsilon_(epsilon),
        cull_(settings.shaft_culling) {
    side_ = std::max(
        1, static_cast<int>(std::ceil(std::sqrt(std::max(1, settings.visibility_samples)))));
    seed_ = settings.seed;
    const Scene& scene = caster.scene();
    in_plane_ = scene.tolerance().in_plane;
    pieces_ = mirror_pieces(scene);
    chains_ = mirror_chains(pieces_, scene.mirror_depth, in_plane_);
  }

  /// Form factor from a receiver point (on polygon `polygon`) to the patch, times the mean
  /// over the shadow rays of what passes along each (0 or 1 through opaque polygons, the
  /// product of the transmittances through filters, 000 §2.2), per channel; plus the same
  /// from the patch's images in every chain of mirrors (000 §3: the image method), times the
  /// chain's specular reflectance. `key` selects the jitter stream.
  Rgb visible_form_factor(const Vec3& x, const Vec3& n, int polygon, const Patch& shooter,
                          uint64_t key) const {
    Rgb ff = direct_form_factor(x, n, polygon, shooter, key);
    for (size_t c = 0; c < chains_.size(); ++c)
      ff += image_form_factor(x, n, shooter, chains_[c], splitmix64(key ^ (c + 1)));
    return ff;
  }

  /// Pairs asked about, and those no polygon could hide: (visibility_pairs, unhidden_pairs).
  std::pair<long long, long long> counts() const { return {pairs_.load(), unhidden_.load()}; }

 private:
  /// The image of the shooter seen from x along the chain m_1 .. m_k (x -> m_1 -> ... -> m_k
  /// -> shooter): y^ = R_1 ... R_k y. A sample ray runs from x to y^, must cross each m_j's
  /// plane inside its outline in turn (reflected at each), and passes the blockers of every
  /// leg (x -> p_1, p_1 -> p_2, ..., p_k -> y) with their transmittances.
  Rgb image_form_factor(const Vec3& x, const Vec3& n, const Patch& shooter,
                        const std::vector<int>& chain, uint64_t key) const {
    const MirrorPiece& first = pieces_[chain.front()];
    const MirrorPiece& last = pieces_[chain.back()];
    if (!(first.height(x) > in_plane_)) return Rgb::Zero();  // x must face the first mirror
    bool in_front = false;                                   // and the shooter the last
    for (const Vec3& c : shooter.corners) in_front = in_front || last.height(c) > in_plane_;
    if (!in_front) return Rgb::Zero();
    const auto image_of = [&](Vec3 y) {
      for (auto j = chain.rbegin(); j != chain.rend(); ++j) y = pieces_[*j].reflect(y);
      return y;
    };
    std::vector<Vec3> corners;
    for (const Vec3& c : shooter.corners) corners.push_back(image_of(c));
    Vec3 normal = shooter.normal;
    for (auto j = chain.rbegin(); j != chain.rend(); ++j)
      normal = pieces_[*j].reflect_direction(normal);
    if (chain.size() % 2 == 1) std::reverse(corners.begin(), corners.end());
    if (!is_in_front_of(x, corners[0], normal)) return Rgb::Zero();
    const double ff = point_polygon_form_factor(x, n, corners);
    if (!(ff > 0)) return Rgb::Zero();
    Rgb specular = Rgb::Ones();
    for (const int j : chain) specular = specular.cwiseProduct(pieces_[j].specular);
    const Rgb visible = mean_over_samples(shooter, key, [&](const Vec3& y) {
      Vec3 from = x, target = image_of(y);
      Rgb passed = Rgb::Ones();
      for (const int j : chain) {
        const MirrorPiece& m = pieces_[j];
        const double hf = m.height(from), ht = m.height(target);
        if (!(hf > 0 && ht < 0)) {
          passed = Rgb::Zero();
          break;
        }
        const Vec3 p = from + (hf / (hf - ht)) * (target - from);
        if (!in_outline(m, p)) {
          passed = Rgb::Zero();
          break;
        }
        passed = passed.cwiseProduct(leg(from, p));
        from = p;
        target = m.reflect(target);
      }
      if (passed != Rgb::Zero()) passed = passed.cwiseProduct(leg(from, y));
      return passed;
    });
    return specular.cwiseProduct(ff * visible);
  }

  /// The mean of pass(y) over the shadow-ray samples y of the shooter: side^2 strata of its
  /// parameter square, jittered from the stream `key` selects.
  template <typename Pass>
  Rgb mean_over_samples(const Patch& shooter, uint64_t key, const Pass& pass) const {
    uint64_t state = splitmix64(seed_ ^ splitmix64(key));
    Rgb sum = Rgb::Zero();
    for (int a = 0; a < side_; ++a) {
      for (int b = 0; b < side_; ++b) {
        const double u = (a + next_uniform(state)) / side_, v = (b + next_uniform(state)) / side_;
        sum += pass(patch_point(shooter, u, v));
      }
    }
    return sum / (side_ * side_);
  }

  /// What passes between two points (not counting surfaces within epsilon of either end; the
  /// far end with a relative margin too, for grazing rays, whose float hit distance is least
  /// precise).
  Rgb leg(const Vec3& a, const Vec3& b) const {
    const Vec3 d = b - a;
    const double distance = d.norm();
    if (!(distance > 2 * epsilon_)) return Rgb::Ones();
    return caster_.transmittance({a, d / distance}, epsilon_, distance * (1 - 1e-6) - epsilon_,
                                 epsilon_);
  }

  Rgb direct_form_factor(const Vec3& x, const Vec3& n, int polygon, const Patch& shooter,
                         uint64_t key) const {
    if (polygon == shooter.polygon) return Rgb::Zero();  // a planar polygon cannot see itself
    if (!is_in_front_of(x, shooter.corners[0], shooter.normal)) return Rgb::Zero();
    const double ff = point_polygon_form_factor(x, n, shooter.corners);
    if (!(ff > 0)) return Rgb::Zero();
    ++pairs_;
    // Nothing between them: every ray would pass, so cast none.
    if (cull_ && !culling_.may_be_hidden(x, polygon, shooter.corners, shooter.polygon)) {
      ++unhidden_;
      return Rgb::Constant(ff);
    }
    return ff * mean_over_samples(shooter, key, [&](const Vec3& y) { return leg(x, y); });
  }

  const RayCaster& caster_;
  ShadowCulling culling_;
  double epsilon_;
  bool cull_ = true;
  mutable std::atomic<long long> pairs_{0}, unhidden_{0};
  int side_ = 4;
  uint64_t seed_ = 1;
  double in_plane_ = 0;
  std::vector<MirrorPiece> pieces_;
  std::vector<std::vector<int>> chains_;  ///< Of at most Scene::mirror_depth reflections
};

void validate(const SolverSettings& s) {
  auto bad = [](const std::string& what) { throw Error("solver settings: " + what); };
  if (!(s.patch_size > 0 && s.patch_size <= 1)) bad("patch_size must be in (0, 1]");
  if (s.element_levels < 0 || s.element_levels > 6) bad("element_levels must be in [0, 6]");
  if (!(s.refine_threshold >= 0)) bad("refine_threshold must be >= 0");
  if (s.refine_passes < 0 || s.refine_passes > 20) bad("refine_passes must be in [0, 20]");
  if (!(s.min_element_size > 0)) bad("min_element_size must be > 0");
  if (!(s.unshot_fraction > 0 && s.unshot_fraction < 1)) bad("unshot_fraction must be in (0, 1)");
  if (s.max_shots < 0) bad("max_shots must be >= 0");
  if (s.visibility_samples < 1) bad("visibility_samples must be >= 1");
}

}  // namespace

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
        rays_(caster, settings, 1e-5 * diagonal_) {  // offsets ~100x float precision
    solution_.settings = settings;
    solution_.patches = make_patches(scene_, settings.patch_size * diagonal_);
    solution_.elements = make_elements(solution_.patches, settings.element_levels);
    // Initial state: each patch's unshot radiosity and each element's radiosity is its emission.
    for (Patch& p : patches()) {
      p.unshot = material(p.polygon).emission;
      p.radiosity = p.unshot;
      stats().emitted += p.unshot * p.area;
      double area;
      Vec3 centroid;
      element_geometry(p.corners, &area, &centroid);
      patch_bounds_.push_back(bounding_sphere(p.corners, centroid));
    }
    for (Element& e : elements()) e.radiosity = material(e.polygon).emission;
    leaves_ = solution_.leaves();
  }

  /// Shoots until the unshot power is below the target (or the shot limit).
  void shoot_until_converged(const std::function<void(const SolveProgress&)>& progress) {
    const double emitted = stats().emitted.sum();
    while (true) {
      int shooter = -1;
      double largest = 0, remaining = 0;
      for (size_t p = 0; p < patches().size(); ++p) {
        const double power = unshot_power(patches()[p]);
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
        for (const Patch& p : patches()) after += unshot_power(p);
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
    const PatchMesh& m = mesh.mesh();
    std::vector<char> split(mesh.face_count(), 0);
    tbb::parallel_for(0, mesh.face_count(), [&](int f) {
      const Element& el = solution_.elements[mesh.element(f)];
      if (!splittable(el)) return;
      std::vector<int> neighbours;
      for (const auto h : m.fh_range(m.face_handle(f))) {
        const auto opposite = h.opp().face();
        if (!opposite.is_valid()) continue;
        const int g = mesh.element(opposite.idx());
        if (std::find(neighbours.begin(), neighbours.end(), g) == neighbours.end())
          neighbours.push_back(g);
      }
      if (neighbours.size() < 3) return;
      // Fit B(u, v) = a + b u + c v through the neighbours, in the element's plane around its
      // centroid: the prediction at the centroid is a.
      const PlaneFrame frame(el.centroid, solution_.patches[el.patch].normal);
      Eigen::MatrixXd A(neighbours.size(), 3);
      Eigen::MatrixXd B(neighbours.size(), 3);
      for (size_t i = 0; i < neighbours.size(); ++i) {
        const Element& n = solution_.elements[neighbours[i]];
        const Vec2 uv = frame.to_2d(n.centroid);
        A.row(i) << 1.0, uv.x(), uv.y();
        B.row(i) = n.radiosity.transpose();
      }
      const Eigen::Matrix3d normal = A.transpose() * A;
      Eigen::LDLT<Eigen::Matrix3d> ldlt(normal);
      if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > 1e-10)) return;  // neighbours in a line
      const Eigen::Matrix3d fit = ldlt.solve(A.transpose() * B);
      const Rgb predicted = fit.row(0).transpose();
      const double miss = (el.radiosity - predicted).cwiseAbs().maxCoeff();
      split[f] = miss > limit(el.radiosity.cwiseMax(predicted).maxCoeff());
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
    for (const Patch& p : patches()) {
      stats().unshot += p.unshot * p.area;
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
  static double unshot_power(const Patch& p) { return p.unshot.cwiseAbs().sum() * p.area; }

  bool refinement_enabled() const { return settings_.refine_threshold > 0 && reference_ > 0; }
  /// Errors are seen relative to the local brightness: the limit follows the local radiosity,
  /// clamped to [0.1, 1] x B_ref so that dark regions are resolved but black ones are not
  /// chased forever.
  double limit(double local_radiosity) const {
    return settings_.refine_threshold * std::clamp(local_radiosity, 0.1 * reference_, reference_);
  }
  bool splittable(const Element& e) const { return longest_edge(e.corners) > min_size_; }
  void split_into(int e, std::vector<int>& children) {
    split_element(elements(), e);
    const int first = elements()[e].first_child;
    back_irradiance_.resize(elements().size(), Rgb::Zero());
    for (int c = 0; c < 4; ++c) {
      children.push_back(first + c);
      back_irradiance_[first + c] = back_irradiance_[e];  // inherited, as the front's is
    }
    ++stats().refined;
  }
  Rgb visible_ff(const Element& el, const Patch& source, uint64_t key) const {
    return rays_.visible_form_factor(el.centroid, solution_.patches[el.patch].normal, el.polygon,
                                     source, key);
  }

  /// One shot of patch `shooter`'s unshot radiosity to every leaf.
  void shoot(int shooter) {
    Patch& source = patches()[shooter];
    const Rgb delta = source.unshot;
    source.unshot = Rgb::Zero();
    const int shot = stats().shots;

    // Receive at every leaf's centroid; split where this shot is far from linear.
    ff_.resize(elements().size(), Rgb::Zero());
    back_ff_.resize(elements().size(), Rgb::Zero());
    back_irradiance_.resize(elements().size(), Rgb::Zero());
    receive(leaves_, source, shot);
    if (refinement_enabled()) refine_during_shot(shooter, delta, shot);

    // Distribute, serially in element order (deterministic sums).
    Rgb received = Rgb::Zero();
    for (const int e : leaves_) {
      if (ff_[e] == Rgb::Zero() && back_ff_[e] == Rgb::Zero()) continue;
      Element& el = elements()[e];
      const Rgb rho = material(el.polygon).reflectance;
      const Rgb irradiance = delta.cwiseProduct(ff_[e]);
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
      owner.unshot += reflected * (el.area / owner.area);
    }
    stats().escaped += delta * source.area - received;
    source.shot += delta;
    ++stats().shots;
  }

  void receive(const std::vector<int>& which, const Patch& source, int shot) {
    tbb::parallel_for(size_t(0), which.size(), [&](size_t k) {
      const int e = which[k];
      ff_[e] = visible_ff(elements()[e], source, stream_key(shot, e, StreamKind::centre, 0));
      if (absorbs_at_back(elements()[e].polygon))
        back_ff_[e] = back_ff(elements()[e], source, stream_key(shot, e, StreamKind::back, 0));
    });
  }

  /// Splits leaves where linear interpolation from the corners misses this shot's radiosity
  /// at the centre by more than the limit; children receive the shot and re-gather.
  void refine_during_shot(int shooter, const Rgb& delta, int shot) {
    const Patch& source = patches()[shooter];
    const Sphere& sb = patch_bounds_[shooter];
    std::vector<int> candidates = leaves_;
    while (!candidates.empty()) {
      std::vector<char> split(candidates.size(), 0);
      tbb::parallel_for(size_t(0), candidates.size(), [&](size_t k) {
        const int e = candidates[k];
        const Element& el = elements()[e];
        const Rgb rho = material(el.polygon).reflectance;
        const double scale = rho.maxCoeff() * delta.cwiseAbs().maxCoeff();
        const double lim = limit(
            (el.radiosity + rho.cwiseProduct(delta).cwiseProduct(ff_[e])).cwiseAbs().maxCoeff());
        if (scale <= lim || !splittable(el)) return;
        // Largest possible form factor from this element to the shooter (bounding spheres):
        // skip pairs that cannot reach the limit.
        const Sphere eb = bounding_sphere(el.corners, el.centroid);
        const double gap = (eb.centre - sb.centre).norm() - eb.radius - sb.radius;
        const double ff_max =
            gap > 0 ? std::min(1.0, source.area / (std::numbers::pi * gap * gap)) : 1.0;
        if (scale * ff_max <= lim) return;
        // Corners pulled 0.1% towards the centre so no point lies on a neighbouring polygon.
        Rgb mean = Rgb::Zero();
        for (size_t c = 0; c < el.corners.size(); ++c) {
          const Vec3 x = el.corners[c] + 1e-3 * (el.centroid - el.corners[c]);
          mean += rays_.visible_form_factor(
              x, solution_.patches[el.patch].normal, el.polygon, source,
              stream_key(shot, e, StreamKind::corner, static_cast<int>(c)));
        }
        mean /= static_cast<double>(el.corners.size());
        split[k] = scale * (ff_[e] - mean).cwiseAbs().maxCoeff() > lim;
      });
      std::vector<int> children;
      for (size_t k = 0; k < candidates.size(); ++k) {
        if (split[k]) split_into(candidates[k], children);
      }
      if (children.empty()) break;
      ff_.resize(elements().size(), Rgb::Zero());
      back_ff_.resize(elements().size(), Rgb::Zero());
      receive(children, source, shot);
      regather(children);
      candidates = std::move(children);
    }
    leaves_ = solution_.leaves();
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
    tbb::parallel_for(size_t(0), children.size(), [&](size_t k) {
      const Element& el = elements()[children[k]];
      const bool at_back = absorbs_at_back(el.polygon);
      for (size_t j = 0; j < solution_.patches.size(); ++j) {
        const Patch& p = solution_.patches[j];
        if (p.shot == Rgb::Zero()) continue;
        gathered[k] += p.shot.cwiseProduct(visible_ff(
            el, p, stream_key(shot, children[k], StreamKind::regather, static_cast<int>(j))));
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
      owner.unshot += rho.cwiseProduct(power) / owner.area;
    }
  }

  const Scene& scene_;
  const SolverSettings settings_;
  const double diagonal_;
  const double reference_;
  const double min_size_;
  Solution solution_;
  const Shooter rays_;
  std::vector<Sphere> patch_bounds_;
  std::vector<int> leaves_;
  std::vector<Rgb> ff_;               ///< This shot's visible form factor per element, per channel.
  std::vector<Rgb> back_ff_;          ///< The same at the backs of filters' elements...
  std::vector<Rgb> back_irradiance_;  ///< ...and what has reached those backs so far.
};

}  // namespace

std::vector<int> Solution::leaves() const {
  std::vector<int> out;
  for (size_t e = 0; e < elements.size(); ++e) {
    if (elements[e].is_leaf()) out.push_back(static_cast<int>(e));
  }
  return out;
}

Solution solve(const RayCaster& caster, const SolverSettings& settings,
               const std::function<void(const SolveProgress&)>& progress) {
  validate(settings);
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
