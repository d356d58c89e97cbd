#include "radiosity/patch_mesh.h"

#include <Eigen/Cholesky>
#include <OpenMesh/Core/System/omstream.hh>
#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include "geometry/planar.h"
#include "geometry/plane.h"
#include "geometry/tolerance.h"
#include "scene/polygon.h"

namespace rad {
namespace {

/// Unique points of one polygon's elements, bucketed in a hash grid.
class PointSet {
  using Cell = Eigen::Matrix<int64_t, 3, 1>;

 public:
  PointSet(double cell, double tolerance) : cell_(cell), tolerance_(tolerance) {}

  /// The index of the point within tolerance of p, adding p if there is none.
  int find_or_add(const Vec3& p) {
    if (const int found = find(p); found >= 0) return found;
    points_.push_back(p);
    cells_[key(cell_of(p))].push_back(static_cast<int>(points_.size()) - 1);
    return static_cast<int>(points_.size()) - 1;
  }

  /// Points strictly inside segment (a, b) (within tolerance of it), sorted from a to b.
  std::vector<int> on_segment(const Vec3& a, const Vec3& b) const {
    const Cell lo = cell_of(a.cwiseMin(b) - Vec3::Constant(tolerance_));
    const Cell hi = cell_of(a.cwiseMax(b) + Vec3::Constant(tolerance_));
    const Vec3 ab = b - a;
    const double length2 = ab.squaredNorm();
    std::vector<std::pair<double, int>> found;
    const auto consider = [&](int q) {
      const double t = (points_[q] - a).dot(ab) / length2;
      if (t <= 0 || t >= 1) return;
      if ((a + t * ab - points_[q]).norm() > tolerance_) return;
      if ((points_[q] - a).norm() <= tolerance_ || (points_[q] - b).norm() <= tolerance_) return;
      found.emplace_back(t, q);
    };
    // The cell is sized by the polygon's shortest element edge, so a long edge of a polygon
    // that also has a tiny one spans up to (length / cell)^3 cells, more than there are
    // points (a 100 m wall with a 0.1 mm sliver: 10^18). Then the points are scanned instead.
    const Eigen::Vector3d span = (hi - lo).cast<double>() + Vec3::Ones();
    if (span.x() * span.y() * span.z() > static_cast<double>(points_.size())) {
      for (int q = 0; q < size(); ++q) consider(q);
    } else {
      for (int64_t i = lo.x(); i <= hi.x(); ++i) {
        for (int64_t j = lo.y(); j <= hi.y(); ++j) {
          for (int64_t k = lo.z(); k <= hi.z(); ++k) {
            const auto it = cells_.find(key({i, j, k}));
            if (it == cells_.end()) continue;
            for (const int q : it->second) consider(q);
          }
        }
      }
    }
    std::sort(found.begin(), found.end());
    std::vector<int> out;
    for (const auto& f : found) out.push_back(f.second);
    return out;
  }

  const Vec3& point(int i) const { return points_[i]; }
  int size() const { return static_cast<int>(points_.size()); }

 private:
  // 64-bit cells: a tiny cell far from the origin overflows an int.
  Cell cell_of(const Vec3& p) const {
    return {static_cast<int64_t>(std::floor(p.x() / cell_)),
            static_cast<int64_t>(std::floor(p.y() / cell_)),
            static_cast<int64_t>(std::floor(p.z() / cell_))};
  }
  static uint64_t key(const Cell& c) {
    return (static_cast<uint64_t>(c.x() & 0x1FFFFF) << 42) |
           (static_cast<uint64_t>(c.y() & 0x1FFFFF) << 21) |
           static_cast<uint64_t>(c.z() & 0x1FFFFF);
  }
  int find(const Vec3& p) const {
    const Cell c = cell_of(p);
    for (int64_t i = -1; i <= 1; ++i) {
      for (int64_t j = -1; j <= 1; ++j) {
        for (int64_t k = -1; k <= 1; ++k) {
          const auto it = cells_.find(key(c + Cell(i, j, k)));
          if (it == cells_.end()) continue;
          for (const int q : it->second) {
            if ((points_[q] - p).norm() <= tolerance_) return q;
          }
        }
      }
    }
    return -1;
  }

  double cell_;
  double tolerance_;
  std::vector<Vec3> points_;
  std::unordered_map<uint64_t, std::vector<int>> cells_;
};

}  // namespace

ElementMesh::ElementMesh(const Solution& solution, double tolerance) {
  const std::vector<int> leaves = solution.leaves();
  // Group leaves by polygon, keeping leaf order inside each group.
  std::map<int, std::vector<int>> by_polygon;  // polygon -> positions in `leaves`
  for (size_t f = 0; f < leaves.size(); ++f)
    by_polygon[solution.elements[leaves[f]].polygon].push_back(static_cast<int>(f));

  std::vector<std::vector<OpenMesh::VertexHandle>> face_handles(leaves.size());
  for (const auto& [polygon, faces] : by_polygon) {
    double smallest = std::numeric_limits<double>::infinity();
    for (const int f : faces) {
      const auto& c = solution.elements[leaves[f]].corners;
      for (size_t i = 0; i < c.size(); ++i)
        smallest = std::min(smallest, (c[(i + 1) % c.size()] - c[i]).norm());
    }
    PointSet points(std::max(smallest, 4 * tolerance), tolerance);
    std::vector<std::vector<int>> corner_ids(faces.size());
    for (size_t k = 0; k < faces.size(); ++k) {
      for (const Vec3& c : solution.elements[leaves[faces[k]]].corners)
        corner_ids[k].push_back(points.find_or_add(c));
    }
    std::vector<OpenMesh::VertexHandle> handles;
    for (int i = 0; i < points.size(); ++i) {
      const Vec3& p = points.point(i);
      handles.push_back(mesh_.add_vertex(OpenMesh::Vec3d(p.x(), p.y(), p.z())));
    }
    for (size_t k = 0; k < faces.size(); ++k) {
      const auto& ids = corner_ids[k];
      std::vector<OpenMesh::VertexHandle> face;
      for (size_t i = 0; i < ids.size(); ++i) {
        face.push_back(handles[ids[i]]);
        const int next = ids[(i + 1) % ids.size()];
        for (const int t : points.on_segment(points.point(ids[i]), points.point(next)))
          face.push_back(handles[t]);
      }
      face_handles[faces[k]] = std::move(face);
    }
  }
  // Add faces in leaf order so face f is leaf f. OpenMesh refuses a face that would make the
  // mesh non-manifold (an edge already between two faces, as where an imported model's three
  // triangles meet on one edge), and asserts on a face that repeats a vertex (corners merged
  // at the tolerance: a sliver). Such a face gets vertices of its own instead: a seam in the
  // display, but face f stays leaf f. OpenMesh's complaint on stderr is silenced meanwhile:
  // it is handled here, not the user's to read.
  const auto repeats_a_vertex = [](std::vector<OpenMesh::VertexHandle> face) {
    std::sort(face.begin(), face.end());
    return std::adjacent_find(face.begin(), face.end()) != face.end();
  };
  const bool complaints = omerr().is_enabled();
  omerr().disable();
  for (size_t f = 0; f < leaves.size(); ++f) {
    if (repeats_a_vertex(face_handles[f]) || !mesh_.add_face(face_handles[f]).is_valid()) {
      std::vector<OpenMesh::VertexHandle> own;
      for (const auto v : face_handles[f]) own.push_back(mesh_.add_vertex(mesh_.point(v)));
      mesh_.add_face(own);
    }
    face_element_.push_back(leaves[f]);
  }
  if (complaints) omerr().enable();
}

std::vector<int> ElementMesh::face_vertices(int face) const {
  std::vector<int> out;
  for (const auto v : mesh_.fv_range(mesh_.face_handle(face))) out.push_back(v.idx());
  return out;
}

std::vector<Vec3> ElementMesh::face_points(int face) const {
  std::vector<Vec3> out;
  for (const auto v : mesh_.fv_range(mesh_.face_handle(face))) {
    const auto& p = mesh_.point(v);
    out.emplace_back(p[0], p[1], p[2]);
  }
  return out;
}

std::optional<Rgb> ElementMesh::neighbour_plane_at(const Solution& solution, int face) const {
  const Element& el = solution.elements[face_element_[face]];
  std::vector<int> neighbours;
  for (const auto h : mesh_.fh_range(mesh_.face_handle(face))) {
    const auto opposite = h.opp().face();
    if (!opposite.is_valid()) continue;
    const int g = face_element_[opposite.idx()];
    if (std::find(neighbours.begin(), neighbours.end(), g) == neighbours.end())
      neighbours.push_back(g);
  }
  if (neighbours.size() < 3) return std::nullopt;
  const PlaneFrame frame(el.centroid, solution.patches[el.patch].normal);
  Eigen::MatrixXd A(neighbours.size(), 3);
  Eigen::MatrixXd B(neighbours.size(), 3);
  for (size_t i = 0; i < neighbours.size(); ++i) {
    const Element& n = solution.elements[neighbours[i]];
    const Vec2 uv = frame.to_2d(n.centroid);
    A.row(i) << 1.0, uv.x(), uv.y();
    B.row(i) = n.radiosity.transpose();
  }
  const Eigen::Matrix3d normal = A.transpose() * A;
  Eigen::LDLT<Eigen::Matrix3d> ldlt(normal);
  if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > 1e-10)) return std::nullopt;
  const Eigen::Matrix3d fit = ldlt.solve(A.transpose() * B);
  return Rgb(fit.row(0).transpose());
}

std::vector<Rgb> ElementMesh::vertex_radiosity(const Solution& solution,
                                               const std::vector<Rgb>& face_reflectance,
                                               bool with_ambient) const {
  std::vector<Rgb> sum(mesh_.n_vertices(), Rgb::Zero());
  std::vector<double> weight(mesh_.n_vertices(), 0.0);
  for (int f = 0; f < face_count(); ++f) {
    const Element& e = solution.elements[face_element_[f]];
    Rgb value = e.radiosity;
    if (with_ambient) value += face_reflectance[f].cwiseProduct(solution.ambient);
    for (const int v : face_vertices(f)) {
      sum[v] += value * e.area;
      weight[v] += e.area;
    }
  }
  for (size_t v = 0; v < sum.size(); ++v) {
    if (weight[v] > 0) sum[v] /= weight[v];
  }
  return sum;
}

Rgb interpolate_mean_value(const std::vector<Vec3>& polygon, const std::vector<Rgb>& values,
                           const Vec3& normal, const Vec3& point) {
  const PlaneFrame frame(point, normal);
  const size_t n = polygon.size();
  std::vector<Vec2> d(n);
  std::vector<double> r(n);
  double scale = 0;
  for (size_t i = 0; i < n; ++i) {
    d[i] = frame.to_2d(polygon[i]);  // relative to the point (the frame's origin)
    r[i] = d[i].norm();
    scale = std::max(scale, r[i]);
  }
  const double eps = relative::kRounding * scale;
  for (size_t i = 0; i < n; ++i) {
    if (r[i] <= eps) return values[i];
  }
  // tan(alpha_i / 2) for the angle alpha_i at the point between vertices i and i+1.
  std::vector<double> tan_half(n);
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + 1) % n;
    const double cross = cross_2d(d[i], d[j]);
    const double dot = d[i].dot(d[j]);
    if (std::abs(cross) <= relative::kRounding * r[i] * r[j] && dot < 0) {
      // On edge (i, j): linear interpolation of its ends.
      const double t = r[i] / (r[i] + r[j]);
      return (1 - t) * values[i] + t * values[j];
    }
    tan_half[i] = (r[i] * r[j] - dot) / cross;
  }
  Rgb sum = Rgb::Zero();
  double total = 0;
  for (size_t i = 0; i < n; ++i) {
    const double w = (tan_half[(i + n - 1) % n] + tan_half[i]) / r[i];
    sum += w * values[i];
    total += w;
  }
  return sum / total;
}

}  // namespace rad
