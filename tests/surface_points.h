#pragma once
/// Random points on a polygon for the robustness tests: some at a vertex, some on an edge, the
/// rest uniformly inside one of its fan triangles.
#include <random>

#include "scene/polygon.h"

namespace rad::test {

inline Vec3 random_surface_point(const Polygon& p, std::mt19937_64& rng, double vertex_fraction,
                                 double edge_fraction) {
  std::uniform_real_distribution<double> u(0, 1);
  const size_t k = p.vertices.size();
  const double kind = u(rng);
  if (kind < vertex_fraction) return p.vertices[static_cast<size_t>(u(rng) * k) % k];
  if (kind < vertex_fraction + edge_fraction) {
    const size_t e = static_cast<size_t>(u(rng) * k) % k;
    return p.vertices[e] + u(rng) * (p.vertices[(e + 1) % k] - p.vertices[e]);
  }
  const size_t t = 1 + static_cast<size_t>(u(rng) * (k - 2)) % (k - 2);
  double a = u(rng), b = u(rng);
  if (a + b > 1) a = 1 - a, b = 1 - b;
  return p.vertices[0] + a * (p.vertices[t] - p.vertices[0]) +
         b * (p.vertices[t + 1] - p.vertices[0]);
}

}  // namespace rad::test
