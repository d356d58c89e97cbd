#include "localpass/mirror_images.h"

#include <algorithm>
#include <cmath>

#include "geometry/clip.h"
#include "scene/polygon.h"
#include "scene/polygon_faces.h"

namespace rad {
namespace {

/// Clips a convex face to the front of each of `planes` (height > in_plane counts as in front,
/// |height| <= in_plane as on the plane); each new edge along a plane is a boundary: the leg
/// ends there. Empty when nothing of it lies in front, or all of it lies in a plane.
std::optional<EmittingFace> clipped_in_front(const EmittingFace& face,
                                             const std::vector<const MirrorPiece*>& planes,
                                             double in_plane) {
  EmittingFace out = face;
  for (const MirrorPiece* plane : planes) {
    const auto height = [&](const Vec3& p) {
      const double h = plane->height(p);
      return std::abs(h) <= in_plane ? 0.0 : h;
    };
    double highest = 0;
    for (const Vec3& v : out.vertices) highest = std::max(highest, height(v));
    if (!(highest > 0)) return std::nullopt;
    EmittingFace clipped = out;
    clipped.vertices.clear();
    clipped.on_boundary.clear();
    clip_loop(out.vertices, out.vertices.size(), height, interpolated_crossing,
              [&](const Vec3& p, int edge) {
                clipped.vertices.push_back(p);
                clipped.on_boundary.push_back(edge == kEdgeAlongCut ? true : out.on_boundary[edge]);
              });
    if (clipped.vertices.size() < 3 || !(newell_vector(clipped.vertices).norm() > 0))
      return std::nullopt;
    out = std::move(clipped);
  }
  return out;
}

/// The face mapped by the isometry (linear, translation), kept counter-clockwise about its
/// mapped normal: a reflection reverses the loop (edge j of the reversed loop is old edge
/// n-2-j).
EmittingFace mapped(const EmittingFace& face, const Eigen::Matrix3d& linear,
                    const Vec3& translation) {
  EmittingFace out = face;
  const size_t n = face.vertices.size();
  const bool reverses = linear.determinant() < 0;
  for (size_t j = 0; j < n; ++j) {
    const size_t from = reverses ? n - 1 - j : j;
    out.vertices[j] = linear * face.vertices[from] + translation;
    out.on_boundary[j] = reverses ? face.on_boundary[(2 * n - 2 - j) % n] : face.on_boundary[j];
  }
  out.normal = linear * face.normal;
  return out;
}

Polygon polygon_of(const EmittingFace& face, int material, const Polygon& provenance) {
  Polygon p = provenance;  // object and index: messages name the polygon it came from
  p.vertices = face.vertices;
  p.normal = face.normal;
  p.area = 0.5 * newell_vector(face.vertices).norm();
  p.material = material;
  return p;
}

/// Convex hull of 2D points (Andrew's monotone chain), counter-clockwise.
std::vector<Vec2> convex_hull(std::vector<Vec2> points) {
  std::sort(points.begin(), points.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() != b.x() ? a.x() < b.x() : a.y() < b.y();
  });
  const auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Vec2> hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], points[i - 1]) <= 0) --k;
    hull[k++] = points[i - 1];
  }
  hull.resize(k > 1 ? k - 1 : k);
  return hull;
}

/// True when some edge normal of either convex polygon separates them by more than `margin`.
bool separated(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double margin) {
  const auto separates = [&](const std::vector<Vec2>& p, const std::vector<Vec2>& q) {
    for (size_t i = 0; i < p.size(); ++i) {
      const Vec2 e = p[(i + 1) % p.size()] - p[i];
      const Vec2 outward(e.y(), -e.x());  // p counter-clockwise: its outside is to the right
      const double length = outward.norm();
      if (!(length > 0)) continue;
      const double edge = outward.dot(p[i]) / length;
      double nearest = std::numeric_limits<double>::infinity();
      for (const Vec2& v : q) nearest = std::min(nearest, outward.dot(v) / length);
      if (nearest > edge + margin) return true;
    }
    return false;
  };
  return separates(a, b) || separates(b, a);
}

}  // namespace

UnfoldedScene unfold(const Scene& scene, const std::vector<EmittingFace>& faces,
                     const std::vector<MirrorPiece>& pieces, const std::vector<int>& chain,
                     double in_plane) {
  UnfoldedScene out;
  out.scene.path = scene.path;
  out.scene.objects = scene.objects;
  out.scene.camera = scene.camera;
  // Materials: the scene's, their images' (no mirrors among them), the frame's.
  const int count = static_cast<int>(scene.materials.size());
  out.scene.materials = scene.materials;
  for (int i = 0; i < count; ++i) {
    Material image = scene.materials[i];
    image.name += " (mirror image)";
    image.specular = Rgb::Zero();
    out.scene.materials.push_back(image);
  }
  const int frame_material = 2 * count;
  out.scene.materials.push_back(Material{"mirror frame", Rgb::Zero(), Rgb::Zero()});
  const auto add = [&](EmittingFace face, int material, const Polygon& provenance) {
    face.polygon = static_cast<int>(out.scene.polygons.size());
    out.scene.polygons.push_back(polygon_of(face, material, provenance));
    out.faces.push_back(std::move(face));
  };

  // The legs, last first: leg j (1-based, k + 1 the last) lies in front of m_(j-1) and m_j
  // and is mapped by T_j = R_k ... R_j (T_(k+1) the identity).
  const int k = static_cast<int>(chain.size());
  std::vector<Eigen::Matrix3d> linear(k + 2, Eigen::Matrix3d::Identity());
  std::vector<Vec3> translation(k + 2, Vec3::Zero());
  for (int j = k; j >= 1; --j) {
    // T_j = T_(j+1) R_j, with R_j(p) = (I - 2 n n^T) p + 2 offset n.
    const MirrorPiece& m = pieces[chain[j - 1]];
    const Eigen::Matrix3d reflection =
        Eigen::Matrix3d::Identity() - 2 * m.normal * m.normal.transpose();
    linear[j] = linear[j + 1] * reflection;
    translation[j] = linear[j + 1] * (2 * m.offset * m.normal) + translation[j + 1];
    out.specular = out.specular.cwiseProduct(m.specular);
  }
  out.linear = linear[1];
  out.translation = translation[1];
  // A convex polygon clipped to a leg is one convex polygon of the unfolded scene, holding the
  // clipped faces it holds (the local pass culls and clusters by polygon, so a polygon per face
  // would cost it the square of the faces); a concave one is split into a polygon per face
  // (its clip need not be simple).
  std::vector<char> convex(scene.polygons.size(), 0);
  {
    std::vector<int> pieces_of(scene.polygons.size(), 0);
    for (const EmittingFace& f : faces_from_polygons(scene)) ++pieces_of[f.polygon];
    for (size_t p = 0; p < convex.size(); ++p) convex[p] = pieces_of[p] == 1;
  }
  for (int j = k + 1; j >= 1; --j) {
    std::vector<const MirrorPiece*> planes;
    if (j >= 2) planes.push_back(&pieces[chain[j - 2]]);
    if (j <= k) planes.push_back(&pieces[chain[j - 1]]);
    const bool last = j == k + 1;
    // The leg's copy of a face: clipped, mapped (black) on the earlier legs.
    const auto leg_copy = [&](const EmittingFace& clipped) {
      if (last) return clipped;
      EmittingFace image = mapped(clipped, linear[j], translation[j]);
      image.exitance = Rgb::Zero();
      return image;
    };
    std::vector<int> unfolded_polygon(scene.polygons.size(), -1);  // -1: not yet, -2: per face
    for (const EmittingFace& f : faces) {
      const std::optional<EmittingFace> clipped = clipped_in_front(f, planes, in_plane);
      if (!clipped) continue;
      const Polygon& provenance = scene.polygons[f.polygon];
      const int material = provenance.material + (last ? 0 : count);
      int& target = unfolded_polygon[f.polygon];
      if (target == -1) {
        target = -2;
        if (convex[f.polygon]) {
          EmittingFace outline;
          outline.vertices = provenance.vertices;
          outline.on_boundary.assign(provenance.vertices.size(), true);
          outline.normal = provenance.normal;
          if (const auto whole = clipped_in_front(outline, planes, in_plane)) {
            target = static_cast<int>(out.scene.polygons.size());
            out.scene.polygons.push_back(polygon_of(leg_copy(*whole), material, provenance));
          }
        }
      }
      if (target == -2) {
        add(leg_copy(*clipped), material, provenance);
        continue;
      }
      EmittingFace face = leg_copy(*clipped);
      face.polygon = target;
      out.faces.push_back(std::move(face));
    }
  }

  // The frames: at m_j, trapezoids from each outline edge out to a similar polygon that holds
  // the disk of radius `reach` around the outline's centroid c. What a frame must cover lies
  // in the convex hull of the receiver x^(k) and the legs, which holds it.
  Bounds box = out.scene.bounds();
  for (int j = 1; j <= k; ++j) {
    for (const Vec3& v : pieces[chain[j - 1]].outline)
      box.add(linear[j + 1] * v + translation[j + 1]);
  }
  const Bounds scene_box = scene.bounds();  // receivers lie in it: x^(k) in its image
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p((corner & 1) ? scene_box.hi.x() : scene_box.lo.x(),
                 (corner & 2) ? scene_box.hi.y() : scene_box.lo.y(),
                 (corner & 4) ? scene_box.hi.z() : scene_box.lo.z());
    box.add(out.receiver(p));
  }
  for (int j = 1; j <= k; ++j) {
    const MirrorPiece& m = pieces[chain[j - 1]];
    std::vector<Vec3> o;
    for (const Vec3& v : m.outline) o.push_back(linear[j + 1] * v + translation[j + 1]);
    const Vec3 normal = linear[j + 1] * m.normal;
    if (linear[j + 1].determinant() < 0) std::reverse(o.begin(), o.end());
    Vec3 c = Vec3::Zero();
    for (const Vec3& v : o) c += v;
    c /= static_cast<double>(o.size());
    double reach = 0;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 p((corner & 1) ? box.hi.x() : box.lo.x(), (corner & 2) ? box.hi.y() : box.lo.y(),
                   (corner & 4) ? box.hi.z() : box.lo.z());
      reach = std::max(reach, (p - c).norm());
    }
    reach = 2 * reach + extent(o);  // margin: the frame's far edge is seen by nothing
    double inradius = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < o.size(); ++i) {
      const Vec3 e = (o[(i + 1) % o.size()] - o[i]).normalized();
      const Vec3 r = c - o[i];
      inradius = std::min(inradius, (r - r.dot(e) * e).norm());
    }
    const double scale = reach / inradius;
    const Polygon& provenance = scene.polygons[m.polygon];
    for (size_t i = 0; i < o.size(); ++i) {
      const Vec3& a = o[i];
      const Vec3& b = o[(i + 1) % o.size()];
      const Vec3 far_a = c + scale * (a - c), far_b = c + scale * (b - c);
      // b -> a -> far a -> far b is counter-clockwise about the normal (the outline is, and
      // the trapezoid lies outside edge a -> b). Radial edges are inner edges of the frame.
      EmittingFace piece;
      piece.vertices = {b, a, far_a, far_b};
      piece.on_boundary = {true, false, true, false};
      piece.normal = normal;
      add(std::move(piece), frame_material, provenance);
    }
  }
  return out;
}

Eigen::AlignedBox3d sources_in_front(const std::vector<EmittingFace>& faces,
                                     const std::vector<MirrorPiece>& pieces,
                                     const MirrorPiece& mirror, double in_plane) {
  Eigen::AlignedBox3d box;
  const std::vector<const MirrorPiece*> front{&mirror};
  for (const EmittingFace& f : faces) {
    if (f.exitance == Rgb::Zero()) continue;
    if (const auto clipped = clipped_in_front(f, front, in_plane)) {
      for (const Vec3& v : clipped->vertices) box.extend(v);
    }
  }
  for (const MirrorPiece& p : pieces) {
    EmittingFace outline;
    outline.vertices = p.outline;
    outline.on_boundary.assign(p.outline.size(), true);
    outline.normal = p.normal;
    if (const auto clipped = clipped_in_front(outline, front, in_plane)) {
      for (const Vec3& v : clipped->vertices) box.extend(v);
    }
  }
  return box;
}

bool may_see_through(const MirrorPiece& mirror, const Vec3& x_mirrored,
                     const Eigen::AlignedBox3d& sources) {
  if (sources.isEmpty()) return false;
  const double hx = mirror.height(x_mirrored);
  if (!(hx < 0)) return true;  // not behind the plane: no claim
  const PlaneFrame frame(mirror.outline.front(), mirror.normal);
  std::vector<Vec2> projected;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p = sources.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner));
    const double hp = mirror.height(p);
    if (!(hp > 0)) return true;  // the box reaches the plane: every direction may pass
    projected.push_back(frame.to_2d(x_mirrored + (hx / (hx - hp)) * (p - x_mirrored)));
  }
  std::vector<Vec2> outline;
  for (const Vec3& v : mirror.outline) outline.push_back(frame.to_2d(v));
  const double margin = 1e-9 * (extent(mirror.outline) + (sources.max() - sources.min()).norm());
  return !separated(convex_hull(projected), outline, margin);
}

}  // namespace rad
