#pragma once
/// Filters (paper 000 §2.2) checked without the filter code: the identity of independent
/// removals over opaque hemisphere gathers, and seeded filters for random scenes. Shared by the
/// vertex tests and the stability report.
#include <string>
#include <vector>

#include "hemisphere/hemisphere_gatherer.h"
#include "scene/polygon_faces.h"
#include "tests/random_scenes.h"

namespace rad::test {

/// "filter<p>" (appended, not by operator+: GCC 12 warns falsely of overlapping copies there).
inline std::string filter_name(size_t p) {
  std::string name = "filter";
  name += std::to_string(p);
  return name;
}

/// The identity of independent removals: a filter of transmittance T passes a line of sight
/// with weight T and stops it with weight 1 - T, independently of the others; and H is linear in
/// what radiates. So, per channel, H = sum over polygons P that radiate, of sum over subsets S
/// of the filters other than P, of prod_{i in S} T_i prod_{i not in S} (1 - T_i) H_opaque(only
/// P radiating, S removed, the rest opaque): P's own light passes what lies in front of it, and
/// what lies behind it is black then. Each H_opaque is a hemisphere gather of opaque faces: the
/// filter code takes no part.
inline Rgb by_subsets(const Scene& scene, const std::vector<EmittingFace>& all,
                      const std::vector<int>& filters, const Vec3& x, const Vec3& n) {
  std::vector<char> radiates(scene.polygons.size(), 0);
  for (const EmittingFace& f : all) radiates[f.polygon] |= f.exitance != Rgb::Zero();
  Rgb total = Rgb::Zero();
  for (size_t source = 0; source < scene.polygons.size(); ++source) {
    if (!radiates[source]) continue;
    std::vector<int> others;
    for (const int f : filters) {
      if (f != static_cast<int>(source)) others.push_back(f);
    }
    for (unsigned mask = 0; mask < (1u << others.size()); ++mask) {
      Rgb weight = Rgb::Ones();
      std::vector<char> removed(scene.polygons.size(), 0);
      for (size_t i = 0; i < others.size(); ++i) {
        const Rgb& t = scene.materials[scene.polygons[others[i]].material].transmittance;
        if (mask & (1u << i)) {
          weight = weight.cwiseProduct(t);
          removed[others[i]] = 1;
        } else {
          weight = weight.cwiseProduct(Rgb::Ones() - t);
        }
      }
      if (weight == Rgb::Zero()) continue;
      std::vector<EmittingFace> opaque;
      for (const EmittingFace& f : all) {
        if (removed[f.polygon]) continue;
        opaque.push_back(f);
        opaque.back().transmittance = Rgb::Zero();
        if (f.polygon != static_cast<int>(source)) opaque.back().exitance = Rgb::Zero();
      }
      total += weight.cwiseProduct(
          HemisphereGatherer(opaque, scene.tolerance()).gather(x, n).irradiance);
    }
  }
  return total;
}

/// A random transmittance: each channel uniform in [0, 1], sometimes exactly 0 or 1.
inline Rgb random_transmittance(test::RandomSceneMaker& maker) {
  Rgb t;
  for (int c = 0; c < 3; ++c) {
    const int kind = maker.integer(0, 5);
    t[c] = kind == 0 ? 0.0 : kind == 1 ? 1.0 : maker.uniform(0, 1);
  }
  return t;
}

/// Makes the non-emitting polygons of `scene` (but the receiving floor, polygon 0) filters, at
/// most `limit` of them; returns their indices.
inline std::vector<int> make_filters(Scene& scene, test::RandomSceneMaker& maker, size_t limit) {
  std::vector<int> filters;
  for (size_t p = 1; p < scene.polygons.size() && filters.size() < limit; ++p) {
    if (scene.materials[scene.polygons[p].material].is_emitter()) continue;
    scene.materials.push_back(
        Material{filter_name(p), Rgb::Zero(), Rgb::Zero(), random_transmittance(maker)});
    scene.polygons[p].material = static_cast<int>(scene.materials.size()) - 1;
    filters.push_back(static_cast<int>(p));
  }
  return filters;
}

}  // namespace rad::test
