#include "localpass/refraction_images.h"

#include <array>
#include <cmath>

#include "geometry/refraction.h"
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

std::vector<RefractedImage> refracted_images(const Scene& scene,
                                             const std::vector<EmittingFace>& faces,
                                             const std::vector<RefractingFacet>& facets,
                                             const RefractionChain& chain, const Vec3& x,
                                             double in_plane) {
  const int k = static_cast<int>(chain.facets.size());
  // Along the centroid path x -> c_1 -> ... -> c_k: the angle at each facet (eqs. 7-8), what
  // each crossing passes, and the length inside.
  std::vector<std::array<double, 3>> ratio(k);
  Rgb weight = Rgb::Ones(), optical_depth = Rgb::Zero();
  Vec3 from = x;
  bool inside = chain.from_inside;
  for (int j = 0; j < k; ++j) {
    const RefractingFacet& f = facets[chain.facets[j]];
    const Vec3 leg = f.centroid - from;
    const double length = leg.norm();
    const double cos_near = length > 0 ? std::abs(leg.dot(f.normal)) / length : 0;
    if (!(cos_near > 1e-12)) return {};  // edge-on: the facet shows nothing
    const Refraction& r = f.refraction;
    if (inside) optical_depth += length * r.attenuation;
    for (int c = 0; c < 3; ++c) {
      const double eta = inside ? 1 / r.ior[c] : r.ior[c];
      const std::optional<double> depth_ratio_c = depth_ratio(cos_near, eta);
      if (!depth_ratio_c) {
        weight[c] = 0;  // total internal reflection in this channel
        ratio[j][c] = 0;
        continue;
      }
      ratio[j][c] = *depth_ratio_c;
      const double passed = r.fresnel ? fresnel_transmission(cos_near, eta) : r.transmittance[c];
      weight[c] *= passed / (eta * eta);
    }
    inside = !inside;
    from = f.centroid;
  }
  weight = weight.cwiseProduct(Rgb((-optical_depth).array().exp()));

  std::vector<RefractedImage> images;
  std::array<bool, 3> done{};
  for (int c = 0; c < 3; ++c) {
    if (done[c] || !(weight[c] > 0)) continue;
    // The channels with the same ratios at every facet share an image.
    RefractedImage image;
    for (int other = c; other < 3; ++other) {
      bool same = weight[other] > 0;
      for (int j = 0; j < k && same; ++j) same = ratio[j][other] == ratio[j][c];
      if (!same) continue;
      done[other] = true;
      image.weight[other] = weight[other];
    }
    // Leg j lies beyond f_j and before f_(j+1), inside the medium or out; mapped by
    // M_j = M_(j-1) T_j (eq. 9 at f_j, the plane of f_j fixed).
    std::vector<Leg> legs(k + 1);
    std::vector<Aperture> apertures;
    bool leg_inside = chain.from_inside;
    for (int j = 0; j <= k; ++j) {
      if (j >= 1) {
        const RefractingFacet& f = facets[chain.facets[j - 1]];
        legs[j].bounds.push_back(side_of(f, leg_inside));
        const DepthContraction t{f.centroid, f.normal, ratio[j - 1][c]};
        legs[j].linear = legs[j - 1].linear * t.linear();
        legs[j].translation = legs[j - 1].linear * t.translation() + legs[j - 1].translation;
      }
      if (j < k) {
        const RefractingFacet& f = facets[chain.facets[j]];
        legs[j].bounds.push_back(side_of(f, leg_inside));
        apertures.push_back({f.outline, f.normal, f.polygon});
      }
      leg_inside = !leg_inside;
    }
    image.unfolded = unfold_legs(scene, faces, apertures, legs, Eigen::Matrix3d::Identity(),
                                 Vec3::Zero(), in_plane, x);
    images.push_back(std::move(image));
  }
  return images;
}

}  // namespace rad
