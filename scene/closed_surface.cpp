#include "scene/closed_surface.h"

#include <algorithm>
#include <array>
#include <iterator>

namespace rad {

SurfaceClosure surface_closure(const std::vector<Polygon>& polygons, int first, int count) {
  using Key = std::array<double, 6>;  // an edge's two endpoints, exactly as written
  std::vector<Key> edges, reversed;
  SurfaceClosure closure;
  for (int p = first; p < first + count; ++p) {
    const std::vector<Vec3>& v = polygons[p].vertices;
    Vec3 centroid = Vec3::Zero();
    for (size_t i = 0; i < v.size(); ++i) {
      const Vec3 &a = v[i], &b = v[(i + 1) % v.size()];
      edges.push_back({a.x(), a.y(), a.z(), b.x(), b.y(), b.z()});
      reversed.push_back({b.x(), b.y(), b.z(), a.x(), a.y(), a.z()});
      centroid += a;
    }
    centroid /= static_cast<double>(v.size());
    closure.volume += centroid.dot(polygons[p].normal) * polygons[p].area / 3;
  }
  // Each directed edge must meet its reverse once: count, with multiplicity, what the sorted
  // lists do not share.
  std::sort(edges.begin(), edges.end());
  std::sort(reversed.begin(), reversed.end());
  std::vector<Key> shared;
  std::set_intersection(edges.begin(), edges.end(), reversed.begin(), reversed.end(),
                        std::back_inserter(shared));
  closure.unpartnered_edges = static_cast<int>(edges.size() - shared.size());
  return closure;
}

}  // namespace rad
