#include "radiosity/mesher.h"

#include <algorithm>
#include <cmath>

#include "geometry/tolerance.h"
#include "radiosity/contact_cuts.h"
#include "scene/polygon.h"

namespace rad {
namespace {

bool is_convex_quad(const std::vector<Vec3>& v, const Vec3& normal) {
  if (v.size() != 4) return false;
  for (int i = 0; i < 4; ++i) {
    const Vec3 e0 = v[(i + 1) % 4] - v[i];
    const Vec3 e1 = v[(i + 2) % 4] - v[(i + 1) % 4];
    if (!(e0.cross(e1).dot(normal) > 0)) return false;
  }
  return true;
}

int divisions(double length, double size) {
  return std::max(1, static_cast<int>(std::ceil(length / size - relative::kMatch)));
}

Patch make_patch(int polygon, const Vec3& normal, std::vector<Vec3> corners) {
  Patch patch;
  patch.polygon = polygon;
  patch.normal = normal;
  Vec3 centroid;
  element_geometry(corners, &patch.area, &centroid);
  patch.corners = std::move(corners);
  return patch;
}

void grid_patches(const std::vector<Vec3>& corners, const Vec3& normal, int polygon, double size,
                  std::vector<Patch>& out) {
  const Vec3 &a = corners[0], &b = corners[1], &c = corners[2], &d = corners[3];
  const int nu = divisions(std::max((b - a).norm(), (c - d).norm()), size);
  const int nv = divisions(std::max((d - a).norm(), (c - b).norm()), size);
  // Bilinear map (u along a->b, v along a->d); points of a planar quad stay in its plane.
  auto at = [&](int i, int j) {
    const double u = static_cast<double>(i) / nu, v = static_cast<double>(j) / nv;
    return Vec3((1 - u) * (1 - v) * a + u * (1 - v) * b + u * v * c + (1 - u) * v * d);
  };
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      out.push_back(
          make_patch(polygon, normal, {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}));
    }
  }
}

void triangle_patches(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& normal, int polygon,
                      double size, std::vector<Patch>& out) {
  const int k = divisions(longest_edge({a, b, c}), size);
  auto at = [&](int i, int j) {  // barycentric (i/k, j/k) towards b and c
    const double u = static_cast<double>(i) / k, v = static_cast<double>(j) / k;
    return Vec3((1 - u - v) * a + u * b + v * c);
  };
  for (int j = 0; j < k; ++j) {
    for (int i = 0; i + j < k; ++i) {
      out.push_back(make_patch(polygon, normal, {at(i, j), at(i + 1, j), at(i, j + 1)}));
      if (i + j + 1 < k)
        out.push_back(make_patch(polygon, normal, {at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}));
    }
  }
}

}  // namespace

double longest_edge(const std::vector<Vec3>& corners) {
  double longest = 0;
  for (size_t i = 0; i < corners.size(); ++i) {
    longest = std::max(longest, (corners[(i + 1) % corners.size()] - corners[i]).norm());
  }
  return longest;
}

void element_geometry(const std::vector<Vec3>& corners, double* area, Vec3* centroid) {
  // Fan of triangles from corner 0: exact for planar convex 3- and 4-gons.
  double total = 0;
  Vec3 weighted = Vec3::Zero();
  for (size_t i = 1; i + 1 < corners.size(); ++i) {
    const double a = 0.5 * (corners[i] - corners[0]).cross(corners[i + 1] - corners[0]).norm();
    total += a;
    weighted += a * (corners[0] + corners[i] + corners[i + 1]) / 3.0;
  }
  *area = total;
  *centroid = total > 0 ? Vec3(weighted / total) : corners[0];
}

std::vector<Patch> make_patches(const Scene& scene, double patch_size,
                                const std::function<void(double)>& progress) {
  std::vector<Patch> patches;
  const NearPolygons near(scene);
  for (size_t i = 0; i < scene.polygons.size(); ++i) {
    if (progress && i % 1024 == 0) progress(static_cast<double>(i) / scene.polygons.size());
    const Polygon& p = scene.polygons[i];
    const int id = static_cast<int>(i);
    const std::vector<std::vector<Vec3>> pieces = contact_pieces(scene, id, 64, &near);
    if (!pieces.empty()) {
      // Cut along contact lines: each convex piece meshed alone (a quad as a grid, any other
      // piece as a fan of triangles), so no patch straddles a line.
      for (const std::vector<Vec3>& piece : pieces) {
        if (is_convex_quad(piece, p.normal)) {
          grid_patches(piece, p.normal, id, patch_size, patches);
        } else {
          for (size_t k = 1; k + 1 < piece.size(); ++k)
            triangle_patches(piece[0], piece[k], piece[k + 1], p.normal, id, patch_size, patches);
        }
      }
    } else if (is_convex_quad(p.vertices, p.normal)) {
      grid_patches(p.vertices, p.normal, id, patch_size, patches);
    } else if (p.vertices.size() == 3) {
      triangle_patches(p.vertices[0], p.vertices[1], p.vertices[2], p.normal, id, patch_size,
                       patches);
    } else {
      for (const auto& t : triangulate(project_to_plane(p.vertices, p.normal))) {
        triangle_patches(p.vertices[t[0]], p.vertices[t[1]], p.vertices[t[2]], p.normal, id,
                         patch_size, patches);
      }
    }
  }
  return patches;
}

double least_patches(const Scene& scene, double patch_size) {
  double count = 0;
  for (const Polygon& p : scene.polygons)
    // (Less a hair: divisions() lets an edge pass patch_size by its matching tolerance.)
    count += std::max(1.0, std::ceil(p.area / (patch_size * patch_size) * (1 - 1e-6)));
  return count;
}

void split_element(std::vector<Element>& elements, int e) {
  const Element parent = elements[e];  // copy: push_back below may reallocate
  const std::vector<Vec3>& c = parent.corners;
  std::vector<std::vector<Vec3>> children;
  if (c.size() == 4) {
    const Vec3 ab = 0.5 * (c[0] + c[1]), bc = 0.5 * (c[1] + c[2]);
    const Vec3 cd = 0.5 * (c[2] + c[3]), da = 0.5 * (c[3] + c[0]);
    const Vec3 mid = 0.25 * (c[0] + c[1] + c[2] + c[3]);
    children = {{c[0], ab, mid, da}, {ab, c[1], bc, mid}, {mid, bc, c[2], cd}, {da, mid, cd, c[3]}};
  } else {
    const Vec3 ab = 0.5 * (c[0] + c[1]), bc = 0.5 * (c[1] + c[2]), ca = 0.5 * (c[2] + c[0]);
    children = {{c[0], ab, ca}, {ab, c[1], bc}, {ca, bc, c[2]}, {ab, bc, ca}};
  }
  elements[e].first_child = static_cast<int>(elements.size());
  for (auto& corners : children) {
    Element child;
    child.patch = parent.patch;
    child.polygon = parent.polygon;
    child.parent = e;
    child.level = parent.level + 1;
    child.radiosity = parent.radiosity;
    child.irradiance = parent.irradiance;
    element_geometry(corners, &child.area, &child.centroid);
    child.corners = std::move(corners);
    elements.push_back(std::move(child));
  }
}

std::vector<Element> make_elements(const std::vector<Patch>& patches, int levels) {
  std::vector<Element> roots;
  for (size_t p = 0; p < patches.size(); ++p) {
    // Subdivide the patch as a temporary tree and keep its leaves as level-0 elements.
    std::vector<Element> tree(1);
    tree[0].patch = static_cast<int>(p);
    tree[0].polygon = patches[p].polygon;
    tree[0].corners = patches[p].corners;
    element_geometry(tree[0].corners, &tree[0].area, &tree[0].centroid);
    for (int level = 0; level < levels; ++level) {
      const size_t count = tree.size();
      for (size_t e = 0; e < count; ++e) {
        if (tree[e].is_leaf()) split_element(tree, static_cast<int>(e));
      }
    }
    for (Element& e : tree) {
      if (!e.is_leaf()) continue;
      e.parent = -1;
      e.level = 0;
      roots.push_back(std::move(e));
    }
  }
  return roots;
}

}  // namespace rad
