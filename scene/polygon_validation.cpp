#include "scene/polygon_validation.h"

#include <cmath>
#include <sstream>

#include "scene/error.h"
#include "scene/limits.h"

namespace rad {
namespace {

std::string format_point(const Vec3& p) {
  std::ostringstream out;
  out << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return out.str();
}

Polygon finish(std::vector<Vec3> vertices, const Vec3& newell, int material, int object,
               int source_index, int triangle) {
  Polygon p;
  p.vertices = std::move(vertices);
  p.normal = newell.normalized();
  p.area = 0.5 * newell.norm();
  p.material = material;
  p.object = object;
  p.source_index = source_index;
  p.triangle = triangle;
  return p;
}

/// The vertices with consecutive repeats merged (last == first included, common in exported
/// files): points within tol.duplicate_vertex of the polygon's extent `scale` are one.
std::vector<Vec3> merge_repeated(const std::vector<Vec3>& vertices, double scale,
                                 const PolygonTolerances& tol) {
  std::vector<Vec3> distinct;
  for (const Vec3& v : vertices) {
    if (distinct.empty() || (v - distinct.back()).norm() > tol.duplicate_vertex * scale) {
      distinct.push_back(v);
    }
  }
  while (distinct.size() > 1 &&
         (distinct.front() - distinct.back()).norm() <= tol.duplicate_vertex * scale) {
    distinct.pop_back();
  }
  return distinct;
}

bool has_zero_area(const Vec3& newell, double scale, const PolygonTolerances& tol) {
  return !(0.5 * newell.norm() > tol.zero_area * scale * scale);
}

}  // namespace

bool holds_no_area(const std::vector<Vec3>& vertices, const PolygonTolerances& tolerances) {
  for (const Vec3& v : vertices)
    if (!v.allFinite() || !(v.cwiseAbs().maxCoeff() <= limits::kCoordinate)) return false;
  const double scale = extent(vertices);
  const std::vector<Vec3> distinct = merge_repeated(vertices, scale, tolerances);
  return distinct.size() < 3 || has_zero_area(newell_vector(distinct), scale, tolerances);
}

std::vector<Polygon> make_polygons(std::vector<Vec3> vertices, const std::string& where,
                                   int material, int object, int source_index,
                                   std::vector<std::string>& warnings,
                                   const PolygonTolerances& tol) {
  if (vertices.size() < 3) {
    throw InputError(where + ": has " + std::to_string(vertices.size()) +
                     " vertices, a polygon needs at least 3");
  }
  for (size_t i = 0; i < vertices.size(); ++i) {
    if (!vertices[i].allFinite()) {
      throw InputError(where + ": vertex " + std::to_string(i) + " is not finite " +
                       format_point(vertices[i]));
    }
    if (!(vertices[i].cwiseAbs().maxCoeff() <= limits::kCoordinate)) {
      throw InputError(where + ": vertex " + std::to_string(i) + " " + format_point(vertices[i]) +
                       " lies beyond +-1e100, where its lengths and areas overflow");
    }
  }

  const double scale = extent(vertices);
  std::vector<Vec3> distinct = merge_repeated(vertices, scale, tol);
  if (distinct.size() != vertices.size()) {
    warnings.push_back(where + ": merged " + std::to_string(vertices.size() - distinct.size()) +
                       " repeated consecutive vertices");
  }
  if (distinct.size() < 3) {
    throw InputError(where + ": has " + std::to_string(distinct.size()) +
                     " distinct vertices, a polygon needs at least 3");
  }

  const Vec3 newell = newell_vector(distinct);
  if (has_zero_area(newell, scale, tol)) {
    throw InputError(where + ": has zero area (its vertices are collinear or coincident)");
  }
  const Vec3 n = newell.normalized();
  const double deviation = plane_deviation(distinct, n);
  if (deviation > tol.non_planar_limit * scale) {
    std::ostringstream msg;
    msg.precision(3);
    msg << where << ": is not planar (a vertex lies " << deviation << " from the best-fit plane, "
        << deviation / scale << " of the polygon's size; the limit is " << tol.non_planar_limit
        << ")";
    throw InputError(msg.str());
  }

  const std::vector<Vec2> flat = project_to_plane(distinct, n);
  if (auto hit = find_self_intersection(flat, tol.self_touch * scale)) {
    throw InputError(where + ": is self-intersecting (edges " + std::to_string(hit->first) +
                     " and " + std::to_string(hit->second) + " meet)");
  }

  if (deviation <= tol.planar * scale) {
    return {finish(std::move(distinct), newell, material, object, source_index, -1)};
  }

  // Slightly non-planar: split into triangles, each exactly planar (DESIGN.md §5).
  std::ostringstream msg;
  msg.precision(3);
  msg << where << ": is " << deviation << " off plane (" << deviation / scale
      << " of its size); split into " << distinct.size() - 2 << " triangles";
  warnings.push_back(msg.str());
  std::vector<Polygon> triangles;
  int index = 0;
  for (const auto& t : triangulate(flat)) {
    std::vector<Vec3> tri{distinct[t[0]], distinct[t[1]], distinct[t[2]]};
    const Vec3 tri_newell = newell_vector(tri);
    triangles.push_back(
        finish(std::move(tri), tri_newell, material, object, source_index, index++));
  }
  return triangles;
}

}  // namespace rad
