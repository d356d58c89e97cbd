#pragma once
/// Whether a set of polygons bounds a solid (000 §4: a refracting object is a closed polyhedron
/// with its fronts facing out, so that every path that enters it leaves it through a facet).
#include <vector>

#include "scene/polygon.h"

namespace rad {

struct SurfaceClosure {
  /// Directed edges (a -> b, vertices compared exactly) with no polygon holding b -> a: 0 for
  /// a closed, consistently oriented surface. A T-junction or a crack counts its edges here.
  int unpartnered_edges = 0;
  /// Signed volume enclosed, sum over polygons of (c . N) A / 3 (divergence theorem): positive
  /// when the fronts face out.
  double volume = 0;
};

/// The closure of `polygons[first .. first + count)`. Cost O(E log E) in the edges.
SurfaceClosure surface_closure(const std::vector<Polygon>& polygons, int first, int count);

}  // namespace rad
