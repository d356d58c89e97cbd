#include "specular/refraction_images.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

#include "geometry/refraction.h"
#include "geometry/tolerance.h"
#include "scene/polygon.h"
#include "scene/polygon_faces.h"

namespace rad {
namespace {

/// True when some vertex of `a` lies strictly behind `b`'s plane (sign -1) or in front (+1).
bool partly_on_side(const RefractingFacet& a, const RefractingFacet& b, int sign, double in_plane) {
  for (const Vec3& v : a.outline) {
    if (sign * b.height(v) > in_plane) return true;
  }
  return false;
}

/// The point of the convex `facet` nearest to p's projection onto its plane.
Vec3 nearest_point(const RefractingFacet& facet, const Vec3& p) {
  const Vec3 foot = p - facet.height(p) * facet.normal;
  const std::vector<Vec3>& o = facet.outline;
  bool inside = true;
  for (size_t i = 0; i < o.size() && inside; ++i) {
    const Vec3& a = o[i];
    const Vec3& b = o[(i + 1) % o.size()];
    inside = (b - a).cross(foot - a).dot(facet.normal) >= 0;
  }
  if (inside) return foot;
  Vec3 best = o.front();
  for (size_t i = 0; i < o.size(); ++i) {
    const Vec3& a = o[i];
    const Vec3 edge = o[(i + 1) % o.size()] - a;
    const double t =
        std::clamp(edge.dot(foot - a) / std::max(edge.squaredNorm(), 1e-300), 0.0, 1.0);
    const Vec3 q = a + t * edge;
    if ((q - foot).squaredNorm() < (best - foot).squaredNorm()) best = q;
  }
  return best;
}

/// The half-space of a leg bounded by `f`: behind it inside the medium, in front outside.
HalfSpace side_of(const RefractingFacet& f, bool inside) {
  return inside ? HalfSpace{-f.normal, -f.offset} : HalfSpace{f.normal, f.offset};
}

}  // namespace

std::vector<RefractingFacet> refracting_facets(const Scene& scene) {
  std::vector<RefractingFacet> facets;
  for (const EmittingFace& f : faces_from_polygons(scene)) {
    const Polygon& p = scene.polygons[f.polygon];
    const Material& m = scene.materials[p.material];
    if (!m.refracts()) continue;
    RefractingFacet facet;
    facet.polygon = f.polygon;
    facet.object = p.object;
    facet.outline = f.vertices;
    facet.normal = f.normal;
    facet.offset = f.normal.dot(f.vertices.front());
    for (const Vec3& v : f.vertices) facet.centroid += v;
    facet.centroid /= static_cast<double>(f.vertices.size());
    facet.refraction = *m.refraction;
    facets.push_back(std::move(facet));
  }
  return facets;
}

std::vector<std::vector<int>> convex_object_facets(const std::vector<RefractingFacet>& facets,
                                                   double in_plane) {
  std::map<int, std::vector<int>> by_object;
  for (size_t i = 0; i < facets.size(); ++i)
    by_object[facets[i].object].push_back(static_cast<int>(i));
  std::vector<std::vector<int>> out(facets.size());
  for (const auto& [object, members] : by_object) {
    bool convex = true;
    for (const int plane : members) {
      for (const int other : members) {
        for (const Vec3& v : facets[other].outline)
          convex = convex && facets[plane].height(v) <= in_plane;
      }
    }
    if (!convex) continue;
    for (const int f : members) out[f] = members;
  }
  return out;
}

std::vector<RefractionChain> refraction_chains(const std::vector<RefractingFacet>& facets,
                                               int depth, double in_plane) {
  std::vector<RefractionChain> chains;
  const int count = static_cast<int>(facets.size());
  // Depth first, in lexicographic order of facet indices. `inside`: the last crossing led in.
  const auto extend = [&](const auto& self, RefractionChain& chain, bool inside) -> void {
    if (!inside) chains.push_back(chain);  // out again: the sources' side
    if (static_cast<int>(chain.facets.size()) >= depth) return;
    const RefractingFacet& a = facets[chain.facets.back()];
    for (int b = 0; b < count; ++b) {
      if (b == chain.facets.back()) continue;
      const RefractingFacet& f = facets[b];
      const bool next =
          inside ? f.object == a.object && partly_on_side(f, a, -1, in_plane) &&
                       partly_on_side(a, f, -1, in_plane)
                 : partly_on_side(f, a, +1, in_plane) && partly_on_side(a, f, +1, in_plane);
      if (!next) continue;
      chain.facets.push_back(b);
      self(self, chain, !inside);
      chain.facets.pop_back();
    }
  };
  for (int i = 0; i < count && depth > 0; ++i) {
    RefractionChain from_outside{{i}, false};
    extend(extend, from_outside, true);
    RefractionChain from_inside{{i}, true};
    extend(extend, from_inside, false);
  }
  return chains;
}

namespace {

/// Along the centroid path x -> c_1 -> ... -> c_k (or, for a traced path, along the ray x ->
/// c_1 refracted on by Snell's law in each channel): the depth ratio at each facet per channel
/// (eqs. 7-8; 0 past the critical angle), and the weight of the path per channel.
struct PathOptics {
  std::vector<std::array<double, 3>> ratio;
  Rgb weight = Rgb::Ones();
  bool seen = true;  ///< false when the first facet is seen edge-on
};

/// One channel of a path's optics: where its line reaches each facet, the depth ratio there
/// (nothing past the critical angle, edge-on, or where a traced ray meets a facet's plane
/// behind it), and the weight of the crossings; stops at the first facet that passes nothing.
struct ChannelOptics {
  std::vector<double> ratio;  ///< per facet; 0 from the first one that passes nothing on
  double weight = 1;
  double optical_depth = 0;  ///< attenuation x length inside the media
};

/// `through`: the point of the first facet the line from x goes through (its centroid, but for
/// the knob's samples).
ChannelOptics channel_optics(const RefractionPath& path, const Vec3& x, int c,
                             const Vec3& through) {
  const int k = static_cast<int>(path.facets.size());
  ChannelOptics o;
  o.ratio.assign(k, 0);
  Vec3 from = x;
  Vec3 direction = Vec3::Zero();
  bool inside = path.from_inside;
  for (int j = 0; j < k; ++j) {
    const RefractingFacet& f = *path.facets[j];
    // Where the line meets the facet: its centroid on the centroid path (and on the first
    // facet of a traced one), else where the refracted ray meets its plane.
    Vec3 at = j == 0 ? through : f.centroid;
    if (path.traced && j > 0) {
      const double along = direction.dot(f.normal);
      const double t =
          std::abs(along) > relative::kRounding ? (f.offset - f.normal.dot(from)) / along : -1;
      if (!(t > 0)) {  // the ray runs along the facet's plane or away from it
        o.weight = 0;
        return o;
      }
      at = from + t * direction;
    }
    const Vec3 leg = at - from;
    const double length = leg.norm();
    const double cos_near = length > 0 ? std::abs(leg.dot(f.normal)) / length : 0;
    if (!(cos_near > 1e-12)) {  // edge-on: the facet shows nothing
      o.weight = 0;
      return o;
    }
    const Refraction& r = f.refraction;
    if (inside) o.optical_depth += length * r.attenuation[c];
    const double eta = inside ? 1 / r.ior[c] : r.ior[c];
    const std::optional<double> ratio = depth_ratio(cos_near, eta);
    if (!ratio) {  // total internal reflection in this channel
      o.weight = 0;
      return o;
    }
    o.ratio[j] = *ratio;
    const double passed = r.fresnel ? fresnel_transmission(cos_near, eta) : r.transmittance[c];
    o.weight *= passed / (eta * eta);
    if (path.traced) direction = refract(leg / length, f.normal, eta).value_or(Vec3::Zero());
    inside = !inside;
    from = at;
  }
  return o;
}

PathOptics optics_of(const RefractionPath& path, const Vec3& x) {
  PathOptics o;
  const int k = static_cast<int>(path.facets.size());
  o.ratio.resize(k);
  // The first facet seen edge-on shows nothing in any channel.
  const Vec3 first = path.facets.front()->centroid - x;
  const double first_length = first.norm();
  if (!(first_length > 0 &&
        std::abs(first.dot(path.facets.front()->normal)) / first_length > relative::kRounding)) {
    o.seen = false;
    o.weight = Rgb::Zero();
    return o;
  }
  Rgb optical_depth = Rgb::Zero();
  for (int c = 0; c < 3; ++c) {
    const ChannelOptics channel = channel_optics(path, x, c, path.facets.front()->centroid);
    for (int j = 0; j < k; ++j) o.ratio[j][c] = channel.ratio[j];
    o.weight[c] = channel.weight;
    optical_depth[c] = channel.optical_depth;
  }
  o.weight = o.weight.cwiseProduct(Rgb((-optical_depth).array().exp()));
  return o;
}

/// The legs of `path` with the ratios of channel c: leg j lies beyond f_j and before f_(j+1),
/// inside the medium or out, mapped by M_j = M_(j-1) T_j (eq. 9 at f_j, its plane fixed).
std::vector<Leg> legs_of(const RefractionPath& path, const PathOptics& o, int c) {
  const int k = static_cast<int>(path.facets.size());
  std::vector<Leg> legs(k + 1);
  bool inside = path.from_inside;
  for (int j = 0; j <= k; ++j) {
    if (j >= 1) {
      const RefractingFacet& f = *path.facets[j - 1];
      legs[j].bounds.push_back(side_of(f, inside));
      const DepthContraction t{f.centroid, f.normal, o.ratio[j - 1][c]};
      legs[j].linear = legs[j - 1].linear * t.linear();
      legs[j].translation = legs[j - 1].linear * t.translation() + legs[j - 1].translation;
    }
    if (j < k) legs[j].bounds.push_back(side_of(*path.facets[j], inside));
    inside = !inside;
  }
  return legs;
}

/// The channels that share channel c's ratios at every facet (and carry light), as a mask.
Rgb same_ratios(const PathOptics& o, int c) {
  Rgb mask = Rgb::Zero();
  for (int other = 0; other < 3; ++other) {
    bool same = o.weight[other] > 0;
    for (size_t j = 0; j < o.ratio.size() && same; ++j) same = o.ratio[j][other] == o.ratio[j][c];
    if (same) mask[other] = 1;
  }
  return mask;
}

}  // namespace

std::vector<RefractedImage> refracted_images(const Scene& scene,
                                             const std::vector<EmittingFace>& faces,
                                             const RefractionPath& path, const Vec3& x,
                                             double in_plane) {
  const PathOptics o = optics_of(path, x);
  std::vector<RefractedImage> images;
  if (!o.seen) return images;
  std::vector<Aperture> apertures;
  for (const RefractingFacet* f : path.facets)
    apertures.push_back({f->outline, f->normal, f->polygon});
  Rgb done = Rgb::Zero();
  for (int c = 0; c < 3; ++c) {
    if (done[c] > 0 || !(o.weight[c] > 0)) continue;
    const Rgb mask = same_ratios(o, c);
    done += mask;
    RefractedImage image;
    image.weight = o.weight.cwiseProduct(mask);
    image.unfolded = unfold_legs(scene, faces, apertures, legs_of(path, o, c),
                                 Eigen::Matrix3d::Identity(), Vec3::Zero(), in_plane, x);
    images.push_back(std::move(image));
  }
  return images;
}

std::vector<RefractedImage> refracted_images(const Scene& scene,
                                             const std::vector<EmittingFace>& faces,
                                             const std::vector<RefractingFacet>& facets,
                                             const RefractionChain& chain, const Vec3& x,
                                             double in_plane) {
  RefractionPath path{{}, chain.from_inside};
  for (const int f : chain.facets) path.facets.push_back(&facets[f]);
  return refracted_images(scene, faces, path, x, in_plane);
}

bool may_pass(const RefractionPath& path, const Vec3& x) {
  const int k = static_cast<int>(path.facets.size());
  if (k < 2) return true;
  const PathOptics o = optics_of(path, x);
  if (!o.seen) return false;
  // Through the last facet's image (mapped by the leg before it), each earlier facet's image
  // (mapped by the leg after it: the two maps agree on its plane) must be seen.
  Rgb done = Rgb::Zero();
  for (int c = 0; c < 3; ++c) {
    if (done[c] > 0 || !(o.weight[c] > 0)) continue;
    done += same_ratios(o, c);
    const std::vector<Leg> legs = legs_of(path, o, c);
    const auto image = [&](int j, const Leg& leg) {
      std::vector<Vec3> out;
      for (const Vec3& v : path.facets[j]->outline) out.push_back(leg.linear * v + leg.translation);
      return out;
    };
    const std::vector<Vec3> last = image(k - 1, legs[k - 1]);
    bool passes = true;
    for (int j = 0; j < k - 1 && passes; ++j) {
      const std::vector<Vec3> aperture = image(j, legs[j + 1]);
      const Vec3 normal = (aperture[1] - aperture[0]).cross(aperture[2] - aperture[0]).normalized();
      passes = may_show_through(aperture, normal, x, last);
    }
    if (passes) return true;
  }
  return false;
}

std::vector<RefractingFacet> facet_pieces(const RefractingFacet& facet, const Vec3& viewpoint,
                                          bool entering, double tolerance, int max_pieces,
                                          const std::vector<const RefractingFacet*>& beyond) {
  // The spread of the depth ratio over a piece: at each facet of the chain (this one, then
  // `beyond`), along the rays from the viewpoint through the piece refracted on (the traced
  // path), against the ray through its centroid, in the worst facet and channel; infinite where
  // some ray passes and the centroid's does not, or the reverse. The angle is smallest (the
  // ratio's argument cos largest) at the point of the piece nearest the viewpoint's foot on the
  // plane: with the vertices it brackets the range, and it finds a window of light inside a
  // piece whose corners are all past the critical angle.
  RefractionPath chain{{&facet}, !entering, true};
  chain.facets.insert(chain.facets.end(), beyond.begin(), beyond.end());
  const auto spread = [&](const RefractingFacet& piece) {
    std::vector<Vec3> samples = piece.outline;
    samples.push_back(nearest_point(piece, viewpoint));
    double worst = 0;
    for (int c = 0; c < 3; ++c) {
      const ChannelOptics middle = channel_optics(chain, viewpoint, c, piece.centroid);
      for (const Vec3& v : samples) {
        const ChannelOptics corner = channel_optics(chain, viewpoint, c, v);
        if (!(middle.weight > 0) && !(corner.weight > 0)) continue;
        if (!(middle.weight > 0) || !(corner.weight > 0))
          return std::numeric_limits<double>::infinity();
        for (size_t j = 0; j < middle.ratio.size(); ++j)
          worst = std::max(worst, std::abs(corner.ratio[j] - middle.ratio[j]) / middle.ratio[j]);
      }
    }
    return worst;
  };
  // The widest spread first; among equal spreads (those across the critical angle are all
  // infinite) the largest piece, so that the budget goes around the whole critical curve
  // rather than into one point of it. Pieces smaller than 1e-6 of the facet stay whole.
  struct Piece {
    double spread, size;
    RefractingFacet facet;
  };
  const double smallest = relative::kFloat * extent(facet.outline);
  std::vector<Piece> pieces{{spread(facet), extent(facet.outline), facet}};
  while (static_cast<int>(pieces.size()) < max_pieces) {
    auto widest =
        std::max_element(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) {
          return a.spread != b.spread ? a.spread < b.spread : a.size < b.size;
        });
    if (!(widest->spread > tolerance) || !(widest->size > smallest)) break;
    const RefractingFacet whole = widest->facet;
    // Across the longest extent, through the centroid.
    Vec3 across = Vec3::Zero();
    for (const Vec3& a : whole.outline) {
      for (const Vec3& b : whole.outline) {
        if ((b - a).squaredNorm() > across.squaredNorm()) across = b - a;
      }
    }
    across.normalize();
    EmittingFace outline;
    outline.vertices = whole.outline;
    outline.on_boundary.assign(whole.outline.size(), true);
    outline.normal = whole.normal;
    const double offset = across.dot(whole.centroid);
    std::vector<RefractingFacet> halves;
    for (const HalfSpace& side : {HalfSpace{across, offset}, HalfSpace{-across, -offset}}) {
      const std::optional<EmittingFace> half = clipped_to(outline, {side}, 0);
      if (!half) continue;
      RefractingFacet piece = whole;
      piece.outline = half->vertices;
      piece.centroid = Vec3::Zero();
      for (const Vec3& v : piece.outline) piece.centroid += v;
      piece.centroid /= static_cast<double>(piece.outline.size());
      halves.push_back(std::move(piece));
    }
    if (halves.size() < 2) break;  // nothing left to split
    *widest = {spread(halves[0]), extent(halves[0].outline), halves[0]};
    pieces.push_back({spread(halves[1]), extent(halves[1].outline), halves[1]});
  }
  std::vector<RefractingFacet> out;
  for (Piece& piece : pieces) out.push_back(std::move(piece.facet));
  return out;
}

}  // namespace rad
