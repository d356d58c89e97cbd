#include "radiosity/solver.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "radiosity/form_factor.h"
#include "radiosity/mesher.h"
#include "scene/error.h"

namespace rad {
namespace {

/// SplitMix64: a counter-based generator, so every (shot, element, point, sample) has its own
/// stream and the result does not depend on which thread computed it.
uint64_t mix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}
double uniform(uint64_t& state) {
  state = mix(state);
  return static_cast<double>(state >> 11) * 0x1.0p-53;
}

/// A point of a patch at parametric (u, v) in [0, 1]^2: bilinear on quads; on triangles the
/// square is folded onto the triangle (area-preserving up to the fold).
Vec3 patch_point(const Patch& p, double u, double v) {
  const auto& c = p.corners;
  if (c.size() == 4) return (1 - u) * (1 - v) * c[0] + u * (1 - v) * c[1] + u * v * c[2] + (1 - u) * v * c[3];
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

class Shooter {
 public:
  Shooter(const RayCaster& caster, const Solution& solution, const SolverSettings& settings,
          double epsilon)
      : caster_(caster), solution_(solution), epsilon_(epsilon) {
    side_ = std::max(1, static_cast<int>(std::ceil(std::sqrt(std::max(1, settings.visibility_samples)))));
    seed_ = settings.seed;
  }

  /// Form factor from a receiver point (on polygon `polygon`) to the patch, times the fraction
  /// of unblocked shadow rays. `key` selects the jitter stream.
  double visible_form_factor(const Vec3& x, const Vec3& n, int polygon, const Patch& shooter,
                             uint64_t key) const {
    if (polygon == shooter.polygon) return 0;  // a planar polygon cannot see itself
    if (!emitter_faces(shooter.corners[0], shooter.normal, x)) return 0;
    const double ff = point_polygon_form_factor(x, n, shooter.corners);
    if (!(ff > 0)) return 0;
    uint64_t state = mix(seed_ ^ mix(key));
    int visible = 0;
    for (int a = 0; a < side_; ++a) {
      for (int b = 0; b < side_; ++b) {
        const double u = (a + uniform(state)) / side_, v = (b + uniform(state)) / side_;
        const Vec3 y = patch_point(shooter, u, v);
        const Vec3 d = y - x;
        const double distance = d.norm();
        if (!(distance > 2 * epsilon_)) {
          ++visible;
          continue;
        }
        // Stop short of the shooter: a relative margin for grazing rays, whose float hit
        // distance is least precise.
        const double t_max = distance * (1 - 1e-6) - epsilon_;
        if (!caster_.occluded({x, d / distance}, epsilon_, t_max)) ++visible;
      }
    }
    return ff * visible / (side_ * side_);
  }

  const Solution& solution() const { return solution_; }

 private:
  const RayCaster& caster_;
  const Solution& solution_;
  double epsilon_;
  int side_ = 4;
  uint64_t seed_ = 1;
};

uint64_t key_of(int shot, int element, int point) {
  return (static_cast<uint64_t>(shot) << 40) ^ (static_cast<uint64_t>(element) << 4) ^ static_cast<uint64_t>(point);
}

void validate(const SolverSettings& s) {
  auto bad = [](const std::string& what) { throw Error("solver settings: " + what); };
  if (!(s.patch_size > 0 && s.patch_size <= 1)) bad("patch_size must be in (0, 1]");
  if (s.element_levels < 0 || s.element_levels > 6) bad("element_levels must be in [0, 6]");
  if (!(s.refine_threshold >= 0)) bad("refine_threshold must be >= 0");
  if (!(s.min_element_size > 0)) bad("min_element_size must be > 0");
  if (!(s.unshot_fraction > 0 && s.unshot_fraction < 1)) bad("unshot_fraction must be in (0, 1)");
  if (s.max_shots < 0) bad("max_shots must be >= 0");
  if (s.visibility_samples < 1) bad("visibility_samples must be >= 1");
}

}  // namespace

double reference_radiosity(const Scene& scene) {
  const double area = scene.total_area();
  Rgb rho_area = Rgb::Zero();
  for (const Polygon& p : scene.polygons) rho_area += scene.materials[p.material].reflectance * p.area;
  const Rgb power = scene.emitted_power();
  double reference = 0;
  for (int c = 0; c < 3; ++c) {
    reference = std::max(reference, power[c] / area / (1 - rho_area[c] / area));
  }
  return reference;
}

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
  const Scene& scene = caster.scene();
  const double diagonal = scene.bounds().diagonal();
  Solution solution;
  solution.settings = settings;
  solution.patches = make_patches(scene, settings.patch_size * diagonal);
  solution.elements = make_elements(solution.patches, settings.element_levels);
  std::vector<Patch>& patches = solution.patches;
  std::vector<Element>& elements = solution.elements;
  SolveStats& stats = solution.stats;

  // Initial state: every patch's unshot radiosity is its emission, every element's radiosity.
  auto material_of = [&](int polygon) -> const Material& { return scene.materials[scene.polygons[polygon].material]; };
  for (Patch& p : patches) {
    p.unshot = material_of(p.polygon).emission;
    p.radiosity = p.unshot;
    stats.emitted += p.unshot * p.area;
  }
  for (Element& e : elements) e.radiosity = material_of(e.polygon).emission;
  const double emitted_sum = stats.emitted.sum();

  const double epsilon = 1e-5 * diagonal;  // shadow-ray offsets: ~100x float precision
  const double refine_limit = settings.refine_threshold * reference_radiosity(scene);
  const double min_size = settings.min_element_size * diagonal;
  const Shooter shooter_rays(caster, solution, settings, epsilon);
  std::vector<Sphere> patch_bounds;
  for (const Patch& p : patches) {
    double area;
    Vec3 centroid;
    element_geometry(p.corners, &area, &centroid);
    patch_bounds.push_back(bounding_sphere(p.corners, centroid));
  }

  std::vector<int> leaves = solution.leaves();
  std::vector<double> ff;  // this shot's visible form factor per element
  auto unshot_power = [&](const Patch& p) { return p.unshot.sum() * p.area; };

  SolveProgress report;
  report.target_fraction = settings.unshot_fraction;
  while (true) {
    // Choose the shooter: the largest unshot power (ties: the lowest index).
    int shooter = -1;
    double largest = 0, remaining = 0;
    for (size_t p = 0; p < patches.size(); ++p) {
      const double power = unshot_power(patches[p]);
      remaining += power;
      if (power > largest) largest = power, shooter = static_cast<int>(p);
    }
    stats.unshot_fraction = emitted_sum > 0 ? remaining / emitted_sum : 0;
    if (shooter < 0 || stats.unshot_fraction <= settings.unshot_fraction) {
      stats.converged = true;
      break;
    }
    if (stats.shots >= settings.max_shots) break;

    Patch& source = patches[shooter];
    const Rgb delta = source.unshot;
    source.unshot = Rgb::Zero();
    const int shot = stats.shots;

    // Receive at every leaf's centroid.
    ff.resize(elements.size());
    auto receive = [&](const std::vector<int>& which) {
      tbb::parallel_for(size_t(0), which.size(), [&](size_t k) {
        const int e = which[k];
        const Element& el = elements[e];
        ff[e] = shooter_rays.visible_form_factor(el.centroid, patches[el.patch].normal, el.polygon, source,
                                                 key_of(shot, e, 0));
      });
    };
    receive(leaves);

    // Adaptive refinement: split leaves where this shot's radiosity is far from linear.
    if (refine_limit > 0) {
      std::vector<int> candidates = leaves;
      const Sphere& sb = patch_bounds[shooter];
      while (!candidates.empty()) {
        std::vector<char> split(candidates.size(), 0);
        tbb::parallel_for(size_t(0), candidates.size(), [&](size_t k) {
          const int e = candidates[k];
          const Element& el = elements[e];
          const double rho = material_of(el.polygon).reflectance.maxCoeff();
          const double scale = rho * delta.maxCoeff();
          if (scale <= refine_limit || longest_edge(el.corners) <= min_size) return;
          // Largest possible form factor from this element to the shooter (bounding spheres):
          // skip pairs that cannot reach the limit.
          const Sphere eb = bounding_sphere(el.corners, el.centroid);
          const double gap = (eb.centre - sb.centre).norm() - eb.radius - sb.radius;
          const double ff_max = gap > 0 ? std::min(1.0, source.area / (std::numbers::pi * gap * gap)) : 1.0;
          if (scale * ff_max <= refine_limit) return;
          // Corners pulled 0.1% towards the centre so no point lies on a neighbouring polygon.
          double mean = 0;
          for (size_t c = 0; c < el.corners.size(); ++c) {
            const Vec3 x = el.corners[c] + 1e-3 * (el.centroid - el.corners[c]);
            mean += shooter_rays.visible_form_factor(x, patches[el.patch].normal, el.polygon, source,
                                                     key_of(shot, e, static_cast<int>(c) + 1));
          }
          mean /= static_cast<double>(el.corners.size());
          split[k] = scale * std::abs(ff[e] - mean) > refine_limit;
        });
        std::vector<int> children;
        for (size_t k = 0; k < candidates.size(); ++k) {
          if (!split[k]) continue;
          split_element(elements, candidates[k]);
          const int first = elements[candidates[k]].first_child;
          for (int c = 0; c < 4; ++c) children.push_back(first + c);
          ++stats.refined;
        }
        if (children.empty()) break;
        ff.resize(elements.size());
        receive(children);
        candidates = std::move(children);
      }
      leaves = solution.leaves();
    }

    // Distribute, serially in element order (deterministic sums).
    const Rgb shot_power = delta * source.area;
    Rgb received = Rgb::Zero();
    for (const int e : leaves) {
      Element& el = elements[e];
      if (ff[e] == 0) continue;
      const Rgb rho = material_of(el.polygon).reflectance;
      const Rgb irradiance = delta * ff[e];
      const Rgb reflected = rho.cwiseProduct(irradiance);
      el.radiosity += reflected;
      received += irradiance * el.area;
      stats.absorbed += (Rgb::Ones() - rho).cwiseProduct(irradiance) * el.area;
      Patch& owner = patches[el.patch];
      owner.unshot += reflected * (el.area / owner.area);
    }
    stats.escaped += shot_power - received;
    ++stats.shots;

    if (progress) {
      report.shots = stats.shots;
      double after = 0;
      for (const Patch& p : patches) after += unshot_power(p);
      report.unshot_fraction = after / emitted_sum;
      report.elements = static_cast<int>(leaves.size());
      progress(report);
    }
  }

  // Patch radiosity: area-weighted mean of its leaves; ledger and ambient term.
  Rgb area_rho = Rgb::Zero();
  double total_area = 0;
  for (Patch& p : patches) p.radiosity = Rgb::Zero();
  for (const int e : leaves) {
    const Element& el = elements[e];
    patches[el.patch].radiosity += el.radiosity * (el.area / patches[el.patch].area);
  }
  for (const Patch& p : patches) {
    stats.unshot += p.unshot * p.area;
    area_rho += material_of(p.polygon).reflectance * p.area;
    total_area += p.area;
  }
  // Cohen et al. 1988: the unshot power, spread over the scene and multiplied out by the
  // interreflection factor R = 1 / (1 - mean rho). Display only; never in the solution values.
  for (int c = 0; c < 3; ++c) {
    const double mean_rho = area_rho[c] / total_area;
    solution.ambient[c] = stats.unshot[c] / total_area / (1 - mean_rho);
  }
  stats.patches = static_cast<int>(patches.size());
  stats.elements = static_cast<int>(leaves.size());
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return solution;
}

}  // namespace rad
