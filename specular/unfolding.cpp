#include "specular/unfolding.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/clip.h"
#include "scene/polygon.h"
#include "scene/polygon_faces.h"

namespace rad {
namespace {

/// A unit normal under the linear map: an orthogonal map carries it itself, any other by its
/// inverse transpose.
Vec3 mapped_normal(const Eigen::Matrix3d& linear, const Vec3& normal) {
  const bool orthogonal =
      (linear.transpose() * linear - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-12;
  if (orthogonal) return linear * normal;
  return (linear.inverse().transpose() * normal).normalized();
}

/// The face mapped by the affine map (linear, translation), kept counter-clockwise about its
/// mapped normal: a map that reverses orientation (a reflection) reverses the loop (edge j of
/// the reversed loop is old edge n-2-j).
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
  out.normal = mapped_normal(linear, face.normal);
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

bool may_show_through(const std::vector<Vec3>& outline, const Vec3& normal, const Vec3& x,
                      const std::vector<Vec3>& points) {
  const double offset = normal.dot(outline.front());
  const double hx = normal.dot(x) - offset;
  if (hx == 0 || points.empty()) return !points.empty();
  const PlaneFrame frame(outline.front(), normal);
  std::vector<Vec2> projected;
  for (const Vec3& p : points) {
    // The line from x through p meets the plane at x + t (p - x), t = hx / (hx - hp): ahead of
    // x when p is nearer the plane than x is, or beyond it.
    const double hp = normal.dot(p) - offset;
    const double t = hx / (hx - hp);
    if (!(t > 0) || !std::isfinite(t)) return true;  // no claim
    projected.push_back(frame.to_2d(x + t * (p - x)));
  }
  std::vector<Vec2> aperture;
  for (const Vec3& v : outline) aperture.push_back(frame.to_2d(v));
  if (signed_area_2d(aperture) < 0) std::reverse(aperture.begin(), aperture.end());
  double reach = extent(outline);
  for (const Vec3& p : points) reach = std::max(reach, (p - x).norm());
  return !separated(convex_hull(projected), aperture, 1e-9 * reach);
}

std::optional<EmittingFace> clipped_to(const EmittingFace& face,
                                       const std::vector<HalfSpace>& bounds, double in_plane) {
  EmittingFace out = face;
  for (const HalfSpace& plane : bounds) {
    const auto height = [&](const Vec3& p) {
      const double h = plane.height(p);
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

UnfoldedScene unfold_legs(const Scene& scene, const std::vector<EmittingFace>& faces,
                          const std::vector<Aperture>& apertures, const std::vector<Leg>& legs,
                          const Eigen::Matrix3d& receiver_linear, const Vec3& receiver_translation,
                          double in_plane, const std::optional<Vec3>& crossing_from) {
  UnfoldedScene out;
  out.linear = receiver_linear;
  out.translation = receiver_translation;
  out.scene.path = scene.path;
  out.scene.objects = scene.objects;
  out.scene.camera = scene.camera;
  out.scene.mirror_depth = 0;
  out.scene.refraction_depth = 0;
  // Materials: the scene's, their images' (no mirrors, no refraction among them), the frame's.
  const int count = static_cast<int>(scene.materials.size());
  out.scene.materials = scene.materials;
  for (int i = 0; i < count; ++i) {
    Material image = scene.materials[i];
    image.name += " (image)";
    image.specular = Rgb::Zero();
    image.refraction.reset();
    out.scene.materials.push_back(image);
  }
  const int frame_material = 2 * count;
  out.scene.materials.push_back(Material{"aperture frame", Rgb::Zero(), Rgb::Zero()});
  // A flattened face (a contraction to depth 0) has no area to radiate or hide anything.
  const auto has_area = [](const EmittingFace& f) { return newell_vector(f.vertices).norm() > 0; };
  const auto add = [&](EmittingFace face, int material, const Polygon& provenance) {
    face.polygon = static_cast<int>(out.scene.polygons.size());
    out.scene.polygons.push_back(polygon_of(face, material, provenance));
    out.faces.push_back(std::move(face));
  };

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
  const int k = static_cast<int>(apertures.size());
  // With a fixed receiver: the far side of each aperture's image plane, seen from it.
  std::vector<HalfSpace> beyond_aperture;
  if (crossing_from) {
    for (int j = 0; j < k; ++j) {
      const Leg& next = legs[j + 1];
      HalfSpace plane{mapped_normal(next.linear, apertures[j].normal), 0};
      plane.offset =
          plane.normal.dot(next.linear * apertures[j].outline.front() + next.translation);
      if (plane.height(*crossing_from) > 0) plane = {-plane.normal, -plane.offset};
      beyond_aperture.push_back(plane);
    }
  }
  // With a fixed receiver, every line that carries light passes the first aperture: a face
  // whose image it cannot see through that outline neither lights nor hides anything.
  std::vector<Vec3> first_outline;
  Vec3 first_normal = Vec3::UnitZ();
  if (crossing_from && k > 0) {
    for (const Vec3& v : apertures[0].outline)
      first_outline.push_back(legs[1].linear * v + legs[1].translation);
    first_normal = mapped_normal(legs[1].linear, apertures[0].normal);
  }
  const auto seen_through_first = [&](const std::vector<Vec3>& image) {
    return first_outline.empty() ||
           may_show_through(first_outline, first_normal, *crossing_from, image);
  };
  // Point lights radiate on the last leg only, mapped like its faces: a light seen in a
  // mirror is its image (000 §3, the image method, exact for a point). A mirror chain's local
  // pass over the unfolded scene decides their visibility through the black frames of the
  // apertures exactly; refraction images are gathered by their faces only and leave them out.
  const auto strictly_inside = [&](const std::vector<HalfSpace>& sides, const Vec3& p) {
    return std::all_of(sides.begin(), sides.end(),
                       [&](const HalfSpace& side) { return side.height(p) > in_plane; });
  };
  for (const PointLight& light : scene.lights) {
    if (!strictly_inside(legs[k].bounds, light.position)) continue;
    PointLight image = light;
    image.position = legs[k].linear * light.position + legs[k].translation;
    if (strictly_inside(beyond_aperture, image.position)) out.scene.lights.push_back(image);
  }
  for (int j = k; j >= 0; --j) {
    const Leg& leg = legs[j];
    const bool last = j == k;
    const std::vector<HalfSpace> crossed(beyond_aperture.begin(),
                                         beyond_aperture.begin() + (crossing_from ? j : 0));
    // The leg's copy of a face: clipped, mapped, clipped to beyond the apertures before it;
    // black on the earlier legs. Empty when nothing is left.
    const auto leg_copy = [&](const EmittingFace& clipped) -> std::optional<EmittingFace> {
      std::optional<EmittingFace> image =
          clipped_to(mapped(clipped, leg.linear, leg.translation), crossed, in_plane);
      if (image && !last) image->exitance = Rgb::Zero();
      return image;
    };
    std::vector<int> unfolded_polygon(scene.polygons.size(), -1);  // -1: not yet, -2: per face
    std::vector<Vec3> whole_image;
    for (const EmittingFace& f : faces) {
      if (!first_outline.empty()) {
        // The whole face's image first: its clip lies in it (cheaper than clipping them all).
        whole_image.clear();
        for (const Vec3& v : f.vertices) whole_image.push_back(leg.linear * v + leg.translation);
        if (!seen_through_first(whole_image)) continue;
      }
      const std::optional<EmittingFace> clipped = clipped_to(f, leg.bounds, in_plane);
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
          if (const auto whole = clipped_to(outline, leg.bounds, in_plane)) {
            const std::optional<EmittingFace> image = leg_copy(*whole);
            if (image && has_area(*image)) {
              target = static_cast<int>(out.scene.polygons.size());
              out.scene.polygons.push_back(polygon_of(*image, material, provenance));
            }
          }
        }
      }
      std::optional<EmittingFace> face = leg_copy(*clipped);
      if (!face || !has_area(*face) || !seen_through_first(face->vertices)) continue;
      if (target == -2) {
        add(std::move(*face), material, provenance);
        continue;
      }
      face->polygon = target;
      out.faces.push_back(std::move(*face));
    }
  }

  // The frames: at aperture j, trapezoids from each outline edge out to a similar polygon that
  // holds the disk of radius `reach` around the outline's centroid c. What a frame must cover
  // lies in the convex hull of the receiver and the legs, which holds it.
  const auto frame_outline = [&](int j) {
    const Leg& beyond = legs[j + 1];
    std::vector<Vec3> o;
    for (const Vec3& v : apertures[j].outline) o.push_back(beyond.linear * v + beyond.translation);
    if (beyond.linear.determinant() < 0) std::reverse(o.begin(), o.end());
    return o;
  };
  Bounds box = out.scene.bounds();
  for (int j = 0; j < k; ++j) {
    for (const Vec3& v : frame_outline(j)) box.add(v);
  }
  const Bounds scene_box = scene.bounds();  // receivers lie in it: their images in its image
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p((corner & 1) ? scene_box.hi.x() : scene_box.lo.x(),
                 (corner & 2) ? scene_box.hi.y() : scene_box.lo.y(),
                 (corner & 4) ? scene_box.hi.z() : scene_box.lo.z());
    box.add(out.receiver(p));
  }
  for (int j = 0; j < k; ++j) {
    const Aperture& a = apertures[j];
    const std::vector<Vec3> o = frame_outline(j);
    const Vec3 normal = mapped_normal(legs[j + 1].linear, a.normal);
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
    const Polygon& provenance = scene.polygons[a.polygon];
    for (size_t i = 0; i < o.size(); ++i) {
      const Vec3& p = o[i];
      const Vec3& q = o[(i + 1) % o.size()];
      const Vec3 far_p = c + scale * (p - c), far_q = c + scale * (q - c);
      // q -> p -> far p -> far q is counter-clockwise about the normal (the outline is, and
      // the trapezoid lies outside edge p -> q). Radial edges are inner edges of the frame.
      EmittingFace piece;
      piece.vertices = {q, p, far_p, far_q};
      piece.on_boundary = {true, false, true, false};
      piece.normal = normal;
      add(std::move(piece), frame_material, provenance);
    }
  }
  return out;
}

}  // namespace rad
