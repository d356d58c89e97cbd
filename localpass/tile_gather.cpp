// The tile's certified interpolation (localpass/tile_gather.h proves it): the cut into smooth
// and rest clusters over the tile's box, the smooth part gathered at the corners, and each
// point's rest gathered with the interpolated part as a known interval.
#include "localpass/tile_gather.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "geometry/clip.h"
#include "geometry/planar.h"
#include "geometry/tolerance.h"

namespace rad {

KernelVariation kernel_variation(const Eigen::AlignedBox3d& region, const Vec3& n,
                                 const Eigen::AlignedBox3d& box, const Vec3& normal, double a_max) {
  constexpr double infinite = std::numeric_limits<double>::infinity();
  // Every u = y - x with x in the region and y in the box lies in this box.
  const Eigen::AlignedBox3d u_box(box.min() - region.max(), box.max() - region.min());
  const double r2 = u_box.squaredExteriorDistance(Vec3::Zero());
  if (!(r2 > 0)) return {infinite, infinite, infinite};
  const Vec3 m = -normal;
  // P = n . u and Q = m . u are linear and |in-plane part of u| convex: largest at corners.
  double p_max = 0, q_max = 0, in_plane_max = 0;
  for (int k = 0; k < 8; ++k) {
    const Vec3 u = u_box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k));
    const double p = n.dot(u);
    p_max = std::max(p_max, p);
    q_max = std::max(q_max, m.dot(u));
    in_plane_max = std::max(in_plane_max, (u - p * n).norm());
  }
  const double r = std::sqrt(r2), r4 = r2 * r2;
  const double a = std::min(1.0, a_max);
  const double b = std::min(1.0, std::sqrt(std::max(0.0, 1 - std::pow(n.dot(m), 2))) + a);
  const double p = std::min(p_max, r), q = std::min(q_max, r);
  const double s = std::min(in_plane_max + p_max * a, r);
  const double pi = std::numbers::pi;
  KernelVariation v;
  v.curvature =
      (2 * a * b + 8 * (a * q + b * p) * s / r2 + p * q * std::max(4.0, 24 * s * s / r2) / r2) /
      (pi * r4);
  v.gradient = (p + q + 4 * p * q / r) / (pi * r4);
  v.sliver = q / (pi * r4);
  return v;
}

namespace {

/// p as an affine combination of three of the quad's corners: weights (0 for the fourth),
/// the rounding residue |sum l_i v_i - p|, and q = sum |l_i| |v_i - p|^2.
struct Weights {
  std::array<double, 4> l = {0, 0, 0, 0};
  double residue = 0, spread = 0, slope = 0;  ///< slope: largest |n . (v_i - p)| / |v_i - p|
  bool valid = false;
};

Weights weights_in_quad(const std::array<Vec3, 4>& corners, const Vec3& p, const Vec3& n) {
  const PlaneFrame frame(corners[0], n);
  const Vec2 at = frame.to_2d(p);
  Weights best;
  double best_min = -std::numeric_limits<double>::infinity();
  for (const std::array<int, 3> t : {std::array{0, 1, 2}, std::array{0, 2, 3}}) {
    const Vec2 a = frame.to_2d(corners[t[0]]), b = frame.to_2d(corners[t[1]]),
               c = frame.to_2d(corners[t[2]]);
    // A sliver of a triangle (an edge-on cell) gives weights that rounding dominates.
    if (!(std::abs(cross_2d(b - a, c - a)) > 1e-9 * (b - a).norm() * (c - a).norm())) continue;
    const auto weights = barycentric_2d(a, b, c, at);
    if (!weights) continue;
    const double lowest = std::min({(*weights)[0], (*weights)[1], (*weights)[2]});
    if (lowest <= best_min) continue;
    best_min = lowest;
    best = Weights{};
    for (int k = 0; k < 3; ++k) best.l[t[k]] = (*weights)[k];
    best.valid = true;
  }
  // Inside the quad but for rounding: a point outside is left to its own gather.
  if (!best.valid || best_min < -1e-6) return Weights{};
  Vec3 combination = Vec3::Zero();
  for (int i = 0; i < 4; ++i) {
    const Vec3 d = corners[i] - p;
    combination += best.l[i] * corners[i];
    if (best.l[i] == 0) continue;
    best.spread += std::abs(best.l[i]) * d.squaredNorm();
    const double length = d.norm();
    if (length > 0) best.slope = std::max(best.slope, std::abs(n.dot(d)) / length);
  }
  best.residue = (combination - p).norm();
  return best;
}

}  // namespace

class LocalPass::TileGather {
 public:
  TileGather(const LocalPass& pass, const std::array<Vec3, 4>& corners,
             const std::array<LocalPassResult, 4>& at_corners, std::span<const Vec3> points,
             const Vec3& n, double tolerance)
      : pass_(pass),
        clusters_(pass.clusters_.clusters()),
        corners_(corners),
        at_corners_(at_corners),
        points_(points),
        n_(n),
        tolerance_(tolerance) {}

  std::vector<LocalPassResult> run() {
    std::vector<LocalPassResult> results(points_.size());
    const auto on_its_own = [&](size_t i) {
      results[i] = pass_.gather(points_[i], n_, tolerance_);
    };
    double darkest = std::numeric_limits<double>::infinity();
    for (const LocalPassResult& r : at_corners_)
      darkest = std::min(darkest, (r.irradiance - r.bound).maxCoeff());
    // The region: the points within `margin` of the quad (those with weights; the others are
    // gathered on their own), and the box around them.
    std::vector<Weights> weights(points_.size());
    Eigen::AlignedBox3d region;
    for (const Vec3& c : corners_) region.extend(c);
    double slope = 0, spread = 0, margin = 0;
    for (size_t i = 0; i < points_.size(); ++i) {
      weights[i] = weights_in_quad(corners_, points_[i], n_);
      const Weights& w = weights[i];
      if (!w.valid) continue;
      region.extend(points_[i]);
      slope = std::max(slope, w.slope);
      spread = std::max(spread, w.spread);
      // Its distance to the quad is at most that to sum max(l_i, 0) v_i / sum max(l_i, 0).
      Vec3 inside = Vec3::Zero();
      double sum = 0;
      for (int c = 0; c < 4; ++c)
        inside += std::max(w.l[c], 0.0) * corners_[c], sum += std::max(w.l[c], 0.0);
      margin = std::max(margin, (points_[i] - inside / sum).norm());
    }
    margin += relative::kRounding * region.diagonal().norm();
    bool ok = tolerance_ > 0 && darkest > 0 &&
              cut(region, margin, slope, kCurvatureShare * tolerance_ * darkest, spread);
    // A cell pays only when its rest is less work than the plain gather: its roots against
    // the terms a corner's own gather summed (a cost model; either way is certified).
    double plain_work = 0;
    for (const LocalPassResult& r : at_corners_)
      plain_work += 0.25 * (r.clusters + r.gathered_exactly);
    const double rest_work = static_cast<double>(rest_whole_.size() + rest_culled_.size());
    if (pass_.tile_when_it_pays_ && rest_work > plain_work) ok = false;
    if (!ok) {
      for (size_t i = 0; i < points_.size(); ++i) on_its_own(i);
      return results;
    }
    // The smooth part at the corners, each a certified interval [lo_i, hi_i].
    std::array<Rgb, 4> lo, hi;
    const GatherScope smooth_scope{.whole = &smooth_};
    for (int i = 0; i < 4; ++i) {
      const LocalPassResult r =
          pass_.gather_by_clusters(corners_[i], n_, kCornerShare * tolerance_, smooth_scope);
      lo[i] = r.irradiance - r.bound, hi[i] = r.irradiance + r.bound;
    }
    for (size_t i = 0; i < points_.size(); ++i) {
      const Weights& w = weights[i];
      if (!w.valid) {
        on_its_own(i);
        continue;
      }
      // sum l_i f(v_i) lies between these (a negative weight, from rounding, swaps the ends).
      Rgb lower = Rgb::Zero(), upper = Rgb::Zero();
      for (int c = 0; c < 4; ++c) {
        lower += w.l[c] * (w.l[c] >= 0 ? lo[c] : hi[c]);
        upper += w.l[c] * (w.l[c] >= 0 ? hi[c] : lo[c]);
      }
      // f(v_i) lies in [lo_i - sliver, hi_i], and tau(p) in [f(p), f(p) + sliver].
      double weight_sum = 0;
      for (const double l : w.l) weight_sum += std::abs(l);
      const Rgb error = 0.5 * w.spread * curvature_ + w.residue * gradient_ +
                        (1 + weight_sum) * sliver_ + relative::kRounding * upper.cwiseAbs();
      GatherScope scope{.whole = &rest_whole_, .culled = &rest_culled_};
      scope.known_lo = (lower - error).cwiseMax(0.0);  // every term is >= 0
      scope.known_hi = upper + error;
      if (pass_.lights_) {
        const Rgb lights =
            pass_.lights_->irradiance(points_[i], n_, pass_.culling_.candidates(points_[i], n_));
        scope.known_lo += lights, scope.known_hi += lights;
      }
      // Its width alone must leave room under T H; H as the corners' values interpolate it
      // (a guess, to spare a rest gather that cannot meet the rule: the rule is checked after).
      Rgb guess = Rgb::Zero();
      for (int c = 0; c < 4; ++c) guess += w.l[c] * at_corners_[c].irradiance;
      const double half = 0.5 * (scope.known_hi - scope.known_lo).maxCoeff();
      if (!(half <= tolerance_ * guess.maxCoeff())) {
        on_its_own(i);  // the interpolated part alone is too wide
        continue;
      }
      LocalPassResult r = pass_.gather_by_clusters(points_[i], n_, tolerance_, scope);
      // (Written so that a NaN anywhere fails it.)
      if (!(r.bound.maxCoeff() <= tolerance_ * r.irradiance.maxCoeff()) ||
          !r.irradiance.allFinite()) {
        on_its_own(i);
        continue;
      }
      r.interpolated = 1;
      results[i] = r;
    }
    return results;
  }

 private:
  struct Smooth {
    int cluster = -1;
    /// Per channel: bmax face_area M, bmax face_area G, and what the sliver between the
    /// region's lowest and highest horizons can bring
    Rgb curvature, gradient, sliver;
    double cost = 0;  ///< Its largest channel's share of the error: M spread / 2
  };

  /// The tile's cut (tile_gather.h): smooth clusters whose curvature terms sum to at most
  /// `budget` at the widest spread, the rest to be gathered per point. False when nothing is
  /// smooth (no interpolation).
  bool cut(const Eigen::AlignedBox3d& region, double margin, double slope, double budget,
           double spread) {
    const OcclusionCulling& culling = pass_.culling_;
    const double in_plane = pass_.in_plane_;
    // An affine function's range over the region: over the quad's corners, widened by margin.
    const auto range = [&](const auto& height) {
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const Vec3& c : corners_) lo = std::min(lo, height(c)), hi = std::max(hi, height(c));
      return std::pair{lo - margin, hi + margin};
    };
    const auto [region_lo, region_hi] = range([&](const Vec3& x) { return n_.dot(x); });
    const double depth = region_hi - region_lo;  // along n: 0 but for rounding
    // The part of a cluster at or above the region's lowest horizon, boxed: what lies below
    // it brings nothing to any point of the region, seen or hidden.
    const double pad = pass_.tolerance_.pad;
    struct Upper {
      std::vector<Vec3> outline;  ///< Clipped (empty when nothing is left)
      Eigen::AlignedBox3d box;    ///< Around it, grown by the pad
    };
    const auto upper_part = [&](const Cluster& cluster) {
      Upper upper;
      upper.outline = clip_to_halfspace(cluster.outline, region_lo * n_, n_);
      if (upper.outline.size() < 3) return Upper{};
      upper.box = bounding_box(upper.outline);
      upper.box.min().array() -= pad, upper.box.max().array() += pad;
      return upper;
    };
    const auto smooth_entry = [&](int c) {
      const Cluster& cluster = clusters_[c];
      const KernelVariation v =
          kernel_variation(region, n_, upper_part(cluster).box, cluster.normal, slope);
      Smooth s{c, cluster.bmax * (cluster.face_area * v.curvature),
               cluster.bmax * (cluster.face_area * v.gradient),
               cluster.bmax * (cluster.face_area * v.sliver * depth), 0};
      s.cost = 0.5 * spread * s.curvature.maxCoeff();
      return s;
    };
    std::vector<Smooth> heap;
    const auto by_cost = [](const Smooth& a, const Smooth& b) {
      return a.cost != b.cost ? a.cost < b.cost : a.cluster > b.cluster;
    };
    double total = 0;
    // A smooth cluster whose box meets the region's has no finite bound: it is seen whole,
    // but gathered per point.
    const auto add_smooth = [&](int c) {
      const Smooth s = smooth_entry(c);
      if (!std::isfinite(s.cost) || !s.gradient.allFinite() || !s.sliver.allFinite()) {
        rest_whole_.push_back(c);
        return;
      }
      heap.push_back(s);
      total += s.cost;
      std::push_heap(heap.begin(), heap.end(), by_cost);
    };
    // Clusters in the order of what they may bring (bmax times a bound on their form factor
    // from the region), so that the splits go where the light is.
    std::vector<std::pair<double, int>> queue;
    const auto enqueue = [&](int c) {
      const Cluster& cluster = clusters_[c];
      const double r2 =
          std::max(cluster.box.squaredExteriorDistance(region.center()), relative::kRounding);
      queue.emplace_back(cluster.bmax.maxCoeff() * cluster.face_area / r2, -c);
      std::push_heap(queue.begin(), queue.end());
    };
    for (const int root : pass_.clusters_.roots()) enqueue(root);
    int splits = 0;
    while (!queue.empty()) {
      std::pop_heap(queue.begin(), queue.end());
      const int c = -queue.back().second;
      queue.pop_back();
      const Cluster& cluster = clusters_[c];
      if (!(cluster.bmax.maxCoeff() > 0)) continue;
      // In front of its plane (the gatherers' test) at every point of the region, or at none.
      const auto [h_lo, h_hi] =
          range([&](const Vec3& x) { return culling.height(cluster.polygon, x); });
      if (h_hi <= in_plane) continue;  // no point of the region can see its front
      const Upper upper = upper_part(cluster);
      if (upper.outline.empty()) continue;  // under every point's horizon
      const Eigen::AlignedBox3d& box = upper.box;
      const double up_hi = n_.dot(box.center()) + n_.cwiseAbs().dot(0.5 * box.sizes());
      const bool smooth =
          h_lo > in_plane && up_hi > region_hi + in_plane &&
          !culling.may_hide_between(corners_, margin, region, upper.outline, box, cluster.polygon);
      if (smooth) {
        add_smooth(c);
      } else if (!cluster.is_leaf() && ++splits <= kSplits) {
        enqueue(cluster.children[0]);
        enqueue(cluster.children[1]);
      } else {
        rest_culled_.push_back(c);
      }
    }
    // The curvature budget: split the costliest smooth cluster (its children are smooth too:
    // their boxes lie in its box), or hand it to the rest when it is a face or splits run out.
    int opened = 0;
    while (!heap.empty() && total > budget) {
      std::pop_heap(heap.begin(), heap.end(), by_cost);
      const Smooth s = heap.back();
      heap.pop_back();
      total -= s.cost;
      const Cluster& cluster = clusters_[s.cluster];
      if (cluster.is_leaf() || ++opened > kOpenings) {
        rest_whole_.push_back(s.cluster);
        continue;
      }
      for (const int child : cluster.children) {
        if (clusters_[child].bmax.maxCoeff() > 0) add_smooth(child);
      }
    }
    if (heap.empty()) return false;
    curvature_ = gradient_ = sliver_ = Rgb::Zero();
    for (const Smooth& s : heap) {
      smooth_.push_back(s.cluster);
      curvature_ += s.curvature, gradient_ += s.gradient, sliver_ += s.sliver;
    }
    std::ranges::sort(smooth_);  // an order that does not depend on the heap's
    return true;
  }

  /// Of T times the darkest corner's H: what the curvature terms may take (the cut's budget),
  /// and the relative tolerance of the corners' gathers of the smooth part.
  static constexpr double kCurvatureShare = 0.5, kCornerShare = 0.25;
  /// Caps on the cut's work per tile: partly hidden clusters split, smooth ones opened.
  static constexpr int kSplits = 256, kOpenings = 256;

  const LocalPass& pass_;
  const std::vector<Cluster>& clusters_;
  const std::array<Vec3, 4>& corners_;
  const std::array<LocalPassResult, 4>& at_corners_;
  std::span<const Vec3> points_;
  const Vec3 n_;
  const double tolerance_;
  std::vector<int> smooth_, rest_whole_, rest_culled_;
  Rgb curvature_ = Rgb::Zero(), gradient_ = Rgb::Zero(), sliver_ = Rgb::Zero();  ///< Sums
};

bool LocalPass::interpolates() const {
  return mirrors_.empty() && !refracting_ && !glossy_ && occlusion_culling_;
}

std::vector<LocalPassResult> LocalPass::gather_tile(
    const std::array<Vec3, 4>& corners, const std::array<LocalPassResult, 4>& at_corners,
    std::span<const Vec3> points, const Vec3& n, double tolerance) const {
  if (!interpolates()) {
    std::vector<LocalPassResult> results;
    for (const Vec3& p : points) results.push_back(gather(p, n, tolerance));
    return results;
  }
  return TileGather(*this, corners, at_corners, points, n, tolerance).run();
}

}  // namespace rad
