#include "radiosity/shooter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>

#include "geometry/lambert.h"
#include "geometry/plane.h"
#include "geometry/tolerance.h"
#include "radiosity/random_stream.h"
#include "scene/point_lights.h"
#include "scene/polygon.h"

namespace rad {

double sphere_form_factor_bound(const Sphere& receiver, const Vec3& normal, const Sphere& source) {
  const double r = source.radius;
  const double gap = (source.centre - receiver.centre).norm() - receiver.radius - r;  // D - r
  if (!(gap > 0)) return 1.0;
  const double height = normal.dot(source.centre - receiver.centre) + r;  // h + r
  if (!(height > 0)) return 0.0;
  const double sine = r / (gap + r);
  const double cosine = std::sqrt(std::max(0.0, 1 - sine * sine));
  return std::min(sine * sine, 2 * (1 - cosine) * std::min(1.0, height / gap));
}

Vec3 patch_point(const Patch& p, double u, double v) {
  const auto& c = p.corners;
  if (c.size() == 4)
    return (1 - u) * (1 - v) * c[0] + u * (1 - v) * c[1] + u * v * c[2] + (1 - u) * v * c[3];
  if (u + v > 1) u = 1 - u, v = 1 - v;
  return (1 - u - v) * c[0] + u * c[1] + v * c[2];
}

Sphere bounding_sphere(const std::vector<Vec3>& corners, const Vec3& centre) {
  double r = 0;
  for (const Vec3& c : corners) r = std::max(r, (c - centre).norm());
  return {centre, r};
}

namespace {

/// Whether every corner of `p` turns the same way about its normal (no reflex corner; collinear
/// corners allowed).
bool is_convex(const Polygon& p) {
  const size_t n = p.vertices.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec3& a = p.vertices[i];
    const Vec3& b = p.vertices[(i + 1) % n];
    const Vec3& c = p.vertices[(i + 2) % n];
    if ((b - a).cross(c - b).dot(p.normal) < 0) return false;
  }
  return true;
}

}  // namespace

Shooter::Shooter(const RayCaster& caster, const SolverSettings& settings, double epsilon)
    : caster_(caster),
      culling_(caster.scene(), epsilon),
      epsilon_(epsilon),
      cull_(settings.shaft_culling),
      lights_(caster, epsilon) {
  side_ =
      std::max(1, static_cast<int>(std::ceil(std::sqrt(std::max(1, settings.visibility_samples)))));
  seed_ = settings.seed;
  const Scene& scene = caster.scene();
  in_plane_ = scene.tolerance().in_plane;
  pieces_ = mirror_pieces(scene);
  // Glossy surfaces are no mirrors to the solver: what they reflect is redirected, counted in
  // the ledger and not carried (paper 003's transfer is the local pass's).
  std::erase_if(pieces_, [&](const MirrorPiece& piece) {
    return scene.materials[scene.polygons[piece.polygon].material].is_glossy_mirror();
  });
  chains_ = mirror_chains(pieces_, scene.mirror_depth, in_plane_);
  solid_convex_.resize(scene.polygons.size());
  for (size_t i = 0; i < scene.polygons.size(); ++i) {
    const Polygon& p = scene.polygons[i];
    const Material& m = scene.materials[p.material];
    solid_convex_[i] = !m.is_filter() && !m.refracts() && is_convex(p);
  }
}

Rgb Shooter::point_light_irradiance(const Vec3& x, const Vec3& n) const { return lights_(x, n); }

double unblocked_form_factor(const Vec3& x, const Vec3& n, const std::vector<Vec3>& corners,
                             const Vec3& normal) {
  if (!is_in_front_of(x, corners[0], normal)) return 0;
  return point_polygon_form_factor(x, n, corners);
}

Rgb Shooter::visible_form_factor(const Vec3& x, const Vec3& n, int polygon, const Patch& shooter,
                                 uint64_t key, int fewer) const {
  const int side = std::max(1, side_ / std::max(1, fewer));
  Rgb ff = direct_form_factor(x, n, polygon, shooter, key, side);
  for (size_t c = 0; c < chains_.size(); ++c)
    ff += image_form_factor(x, n, shooter, chains_[c], splitmix64(key ^ (c + 1)), side);
  return ff;
}

/// The image of the shooter seen from x along the chain m_1 .. m_k (x -> m_1 -> ... -> m_k
/// -> shooter): y^ = R_1 ... R_k y. A sample ray runs from x to y^, must cross each m_j's
/// plane inside its outline in turn (reflected at each), and passes the blockers of every
/// leg (x -> p_1, p_1 -> p_2, ..., p_k -> y) with their transmittances.
namespace {

/// Probe directions about n: n itself, then eight at `angle` from it.
std::vector<Vec3> probe_directions(const Vec3& x, const Vec3& n, double angle) {
  const PlaneFrame frame(x, n);
  const double tilt = std::sin(angle), lift = std::cos(angle);
  std::vector<Vec3> out{n};
  for (int k = 0; k < 8; ++k) {
    const double a = k * std::numbers::pi / 4;
    out.push_back((lift * n + tilt * (std::cos(a) * frame.u + std::sin(a) * frame.v)).normalized());
  }
  return out;
}

}  // namespace

bool Shooter::is_buried(const Vec3& x, const Vec3& n) const {
  // A point in the open sees the front of some polygon (or the sky) along one of the probes;
  // inside a closed object every probe ends at the back of one of its faces.
  const Vec3 origin = x + 10 * epsilon_ * n;
  for (const Vec3& d : probe_directions(x, n, std::numbers::pi / 3)) {
    const std::optional<Hit> hit = caster_.closest_hit({origin, d}, 0);
    if (!hit || hit->front_facing) return false;
    // A filter does not enclose: light comes through it.
    const Scene& scene = caster_.scene();
    if (scene.materials[scene.polygons[hit->polygon].material].is_filter()) return false;
  }
  return true;
}

bool Shooter::faces_within(const Vec3& x, const Vec3& n, double distance) const {
  const Vec3 origin = x + 10 * epsilon_ * n;
  for (const Vec3& d : probe_directions(x, n, 0.45 * std::numbers::pi)) {
    const std::optional<Hit> hit = caster_.closest_hit({origin, d}, 0, distance);
    if (hit && hit->front_facing) return true;
  }
  return false;
}

Rgb Shooter::image_form_factor(const Vec3& x, const Vec3& n, const Patch& shooter,
                               const std::vector<int>& chain, uint64_t key, int side) const {
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
  const double ff = unblocked_form_factor(x, n, corners, normal);
  if (!(ff > 0)) return Rgb::Zero();
  Rgb specular = Rgb::Ones();
  for (const int j : chain) specular = specular.cwiseProduct(pieces_[j].specular);
  const Rgb visible = mean_over_samples(shooter, key, side, [&](const Vec3& y) {
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
      if (!m.contains(p)) {
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

/// Visits the shadow-ray samples y of the shooter: side^2 strata of its parameter square,
/// jittered from the stream `key` selects.
template <typename Visit>
void Shooter::for_each_sample(const Patch& shooter, uint64_t key, int side,
                              const Visit& visit) const {
  uint64_t state = splitmix64(seed_ ^ splitmix64(key));
  for (int a = 0; a < side; ++a) {
    for (int b = 0; b < side; ++b) {
      const double u = (a + next_uniform(state)) / side, v = (b + next_uniform(state)) / side;
      visit(patch_point(shooter, u, v));
    }
  }
}

/// The mean of pass(y) over the shadow-ray samples y of the shooter.
template <typename Pass>
Rgb Shooter::mean_over_samples(const Patch& shooter, uint64_t key, int side,
                               const Pass& pass) const {
  Rgb sum = Rgb::Zero();
  for_each_sample(shooter, key, side, [&](const Vec3& y) { sum += pass(y); });
  return sum / (side * side);
}

/// The segment a leg from a to b tests (not counting surfaces within epsilon of either end;
/// the far end with a relative margin too, for grazing rays, whose float hit distance is
/// least precise); none when the points are too close for anything to lie between them.
std::optional<RayCaster::Segment> Shooter::leg_segment(const Vec3& a, const Vec3& b) const {
  const Vec3 d = b - a;
  const double distance = d.norm();
  if (!(distance > 2 * epsilon_)) return std::nullopt;
  return RayCaster::Segment{
      {a, d / distance}, epsilon_, distance * (1 - relative::kFloat) - epsilon_};
}

/// What passes between two points.
Rgb Shooter::leg(const Vec3& a, const Vec3& b) const {
  const std::optional<RayCaster::Segment> s = leg_segment(a, b);
  if (!s) return Rgb::Ones();
  return caster_.transmittance(s->ray, s->t_min, s->t_max, epsilon_);
}

/// mean_over_samples of leg(x, y) in a scene without filters (a leg passes all or nothing):
/// the same segments, traced as one coherent stream of rays from x, which Embree traverses
/// as packets (a quarter of the solve's time saved on the Cornell box).
double Shooter::visible_fraction(const Vec3& x, const Patch& shooter, uint64_t key,
                                 int side) const {
  thread_local std::vector<RayCaster::Segment> segments;
  thread_local std::vector<char> blocked;
  segments.clear();
  int passed = 0;
  for_each_sample(shooter, key, side, [&](const Vec3& y) {
    if (const std::optional<RayCaster::Segment> s = leg_segment(x, y)) {
      segments.push_back(*s);
    } else {
      ++passed;
    }
  });
  caster_.occluded(segments, blocked);
  for (const char b : blocked) passed += !b;
  return static_cast<double>(passed) / (side * side);
}

Shooter::PairCounts Shooter::counts() const {
  PairCounts sum;
  for (const PairCounts& c : counts_) {
    sum.pairs += c.pairs, sum.unhidden += c.unhidden, sum.hidden += c.hidden;
  }
  return sum;
}

bool Shooter::something_on_the_way(const Vec3& x, int polygon, const Patch& shooter,
                                   int* blocker) const {
  if (blocker) *blocker = -1;
  Vec3 centre = Vec3::Zero();
  for (const Vec3& c : shooter.corners) centre += c;
  centre /= static_cast<double>(shooter.corners.size());
  const std::optional<RayCaster::Segment> s = leg_segment(x, centre);
  if (!s) return false;
  const std::optional<Hit> hit = caster_.closest_hit(s->ray, s->t_min, s->t_max);
  if (!hit || hit->polygon == polygon || hit->polygon == shooter.polygon) return false;
  if (blocker) *blocker = hit->polygon;
  return true;
}

bool Shooter::hides_all(const Vec3& x, const Patch& shooter, int blocker) const {
  return hides_between(std::span<const Vec3>(&x, 1), shooter.corners, blocker);
}

bool Shooter::hides_between(std::span<const Vec3> from, std::span<const Vec3> to,
                            int blocker) const {
  if (!solid_convex_[blocker] || from.empty()) return false;
  const Polygon& wall = caster_.scene().polygons[blocker];
  const Vec3& origin = wall.vertices[0];
  const auto height = [&](const Vec3& y) { return wall.normal.dot(y - origin); };
  const double side = height(from[0]) > 0 ? 1.0 : -1.0;
  // Every point of `from` strictly on one side, every point of `to` on the other, each by
  // more than epsilon.
  for (const Vec3& a : from) {
    if (!(side * height(a) > epsilon_)) return false;
  }
  for (const Vec3& b : to) {
    if (!(-side * height(b) > epsilon_)) return false;
  }
  // Each edge's inward direction (counter-clockwise about the normal: normal x edge points
  // inward) and epsilon's inset along it.
  struct Edge {
    Vec3 vertex, inward;
    double inset;
  };
  constexpr size_t kHeld = 8;  // (a quad's, a slab's: no allocation)
  std::array<Edge, kHeld> held;
  std::vector<Edge> more;
  const size_t n = wall.vertices.size();
  if (n > kHeld) more.resize(n);
  Edge* edges = n > kHeld ? more.data() : held.data();
  size_t edge_count = 0;
  for (size_t i = 0; i < n; ++i) {
    const Vec3& v = wall.vertices[i];
    const Vec3 inward = wall.normal.cross(wall.vertices[(i + 1) % n] - v);
    const double inset = epsilon_ * inward.norm();
    if (inset > 0) edges[edge_count++] = {v, inward, inset};  // (a repeated vertex: no edge)
  }
  // The crossing of each segment between them with the blocker's plane, inside every edge by
  // more than epsilon.
  for (const Vec3& a : from) {
    const double h_a = height(a);
    for (const Vec3& b : to) {
      const Vec3 crossing = a + (h_a / (h_a - height(b))) * (b - a);
      for (size_t i = 0; i < edge_count; ++i) {
        if (!(edges[i].inward.dot(crossing - edges[i].vertex) > edges[i].inset)) return false;
      }
    }
  }
  return true;
}

Rgb Shooter::direct_form_factor(const Vec3& x, const Vec3& n, int polygon, const Patch& shooter,
                                uint64_t key, int side) const {
  if (polygon == shooter.polygon) return Rgb::Zero();  // a planar polygon cannot see itself
  const double ff = unblocked_form_factor(x, n, shooter.corners, shooter.normal);
  if (!(ff > 0)) return Rgb::Zero();
  PairCounts& counted = counts_.local();
  ++counted.pairs;
  // Nothing between them: every ray would pass, so cast none. (The question goes by reference:
  // a std::function holds that without allocating, once per pair.)
  int blocker = -1;
  const auto on_the_way = [&] { return something_on_the_way(x, polygon, shooter, &blocker); };
  if (cull_ && !culling_.may_be_hidden(x, polygon, shooter.corners, shooter.polygon,
                                       std::cref(on_the_way))) {
    ++counted.unhidden;
    return Rgb::Constant(ff);
  }
  // The polygon the one ray met may hide all of the shooter: then no ray can pass.
  if (blocker >= 0 && hides_all(x, shooter, blocker)) {
    ++counted.hidden;
    return Rgb::Zero();
  }
  if (!caster_.has_filters()) return Rgb::Constant(ff * visible_fraction(x, shooter, key, side));
  return ff * mean_over_samples(shooter, key, side, [&](const Vec3& y) { return leg(x, y); });
}

}  // namespace rad
