#include "specular/unfolding.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/clip.h"
#include "geometry/tolerance.h"
#include "scene/polygon.h"
#include "scene/polygon_faces.h"

namespace rad {
namespace {

/// A unit normal under the linear map: an orthogonal map carries it itself, any other by its
/// inverse transpose.
Vec3 mapped_normal(const Eigen::Matrix3d& linear, const Vec3& normal) {
  const bool orthogonal =
      (linear.transpose() * linear - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <
      relative::kRounding;
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
  std::vector<Vec2> hull;
  for (const int i : convex_hull(projected)) hull.push_back(projected[i]);
  return !separated(hull, aperture, relative::kMatch * reach);
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

namespace {

/// One unfolding (unfold_legs): its inputs, the scene it builds, and its steps.
class Unfolding {
 public:
  Unfolding(const Scene& scene, const std::vector<EmittingFace>& faces,
            const std::vector<Aperture>& apertures, const std::vector<Leg>& legs, double in_plane,
            const std::optional<Vec3>& crossing_from)
      : scene_(scene),
        faces_(faces),
        apertures_(apertures),
        legs_(legs),
        in_plane_(in_plane),
        crossing_from_(crossing_from),
        k_(static_cast<int>(apertures.size())),
        count_(static_cast<int>(scene.materials.size())) {}

  UnfoldedScene run(const Eigen::Matrix3d& receiver_linear, const Vec3& receiver_translation) {
    out_.linear = receiver_linear;
    out_.translation = receiver_translation;
    copy_scene_settings_and_materials();
    find_convex_polygons();
    if (crossing_from_) find_far_sides_and_first_aperture();
    add_lights();
    for (int j = k_; j >= 0; --j) add_leg(j);
    add_frames();
    return std::move(out_);
  }

 private:
  /// The scene's settings, its materials, their images' (no mirrors, no refraction among them:
  /// images never reflect or refract) and the frames'.
  void copy_scene_settings_and_materials() {
    out_.scene.path = scene_.path;
    out_.scene.objects = scene_.objects;
    out_.scene.camera = scene_.camera;
    out_.scene.mirror_depth = 0;
    out_.scene.refraction_depth = 0;
    out_.scene.materials = scene_.materials;
    for (int i = 0; i < count_; ++i) {
      Material image = scene_.materials[i];
      image.name += " (image)";
      image.specular = Rgb::Zero();
      image.refraction.reset();
      out_.scene.materials.push_back(image);
    }
    out_.scene.materials.push_back(Material{"aperture frame", Rgb::Zero(), Rgb::Zero()});
  }
  int frame_material() const { return 2 * count_; }

  /// A convex polygon clipped to a leg is one convex polygon of the unfolded scene, holding the
  /// clipped faces it holds (the local pass culls and clusters by polygon, so a polygon per
  /// face would cost it the square of the faces); a concave one is split into a polygon per
  /// face (its clip need not be simple).
  void find_convex_polygons() {
    convex_.assign(scene_.polygons.size(), 0);
    std::vector<int> pieces_of(scene_.polygons.size(), 0);
    for (const EmittingFace& f : faces_from_polygons(scene_)) ++pieces_of[f.polygon];
    for (size_t p = 0; p < convex_.size(); ++p) convex_[p] = pieces_of[p] == 1;
  }

  /// With a fixed receiver: the far side of each aperture's image plane, seen from it; and the
  /// first aperture's image, which every line that carries light passes: a face whose image the
  /// receiver cannot see through that outline neither lights nor hides anything.
  void find_far_sides_and_first_aperture() {
    for (int j = 0; j < k_; ++j) {
      const Leg& next = legs_[j + 1];
      HalfSpace plane{mapped_normal(next.linear, apertures_[j].normal), 0};
      plane.offset =
          plane.normal.dot(next.linear * apertures_[j].outline.front() + next.translation);
      if (plane.height(*crossing_from_) > 0) plane = {-plane.normal, -plane.offset};
      beyond_aperture_.push_back(plane);
    }
    if (k_ == 0) return;
    for (const Vec3& v : apertures_[0].outline)
      first_outline_.push_back(legs_[1].linear * v + legs_[1].translation);
    first_normal_ = mapped_normal(legs_[1].linear, apertures_[0].normal);
  }

  bool seen_through_first(const std::vector<Vec3>& image) const {
    return first_outline_.empty() ||
           may_show_through(first_outline_, first_normal_, *crossing_from_, image);
  }

  bool strictly_inside(const std::vector<HalfSpace>& sides, const Vec3& p) const {
    return std::all_of(sides.begin(), sides.end(),
                       [&](const HalfSpace& side) { return side.height(p) > in_plane_; });
  }

  /// Point lights radiate on the last leg only, mapped like its faces: a light seen in a
  /// mirror is its image (000 §3, the image method, exact for a point). A mirror chain's local
  /// pass over the unfolded scene decides their visibility through the black frames of the
  /// apertures exactly; refraction images are gathered by their faces only and leave them out.
  void add_lights() {
    for (const PointLight& light : scene_.lights) {
      if (!strictly_inside(legs_[k_].bounds, light.position)) continue;
      PointLight image = light;
      image.position = legs_[k_].linear * light.position + legs_[k_].translation;
      if (strictly_inside(beyond_aperture_, image.position)) out_.scene.lights.push_back(image);
    }
  }

  /// A face of the unfolded scene, as a polygon of its own.
  void add_face(EmittingFace face, int material, const Polygon& provenance) {
    face.polygon = static_cast<int>(out_.scene.polygons.size());
    out_.scene.polygons.push_back(polygon_of(face, material, provenance));
    out_.faces.push_back(std::move(face));
  }

  /// A flattened face (a contraction to depth 0) has no area to radiate or hide anything.
  static bool has_area(const EmittingFace& f) { return newell_vector(f.vertices).norm() > 0; }

  /// Leg j's copies of the faces: each clipped to the leg, mapped, clipped to beyond the
  /// apertures before it; black on the earlier legs.
  void add_leg(int j) {
    const Leg& leg = legs_[j];
    const bool last = j == k_;
    const std::vector<HalfSpace> crossed(beyond_aperture_.begin(),
                                         beyond_aperture_.begin() + (crossing_from_ ? j : 0));
    // The leg's copy of a face; empty when nothing is left.
    const auto leg_copy = [&](const EmittingFace& clipped) -> std::optional<EmittingFace> {
      std::optional<EmittingFace> image =
          clipped_to(mapped(clipped, leg.linear, leg.translation), crossed, in_plane_);
      if (image && !last) image->exitance = Rgb::Zero();
      return image;
    };
    std::vector<int> unfolded_polygon(scene_.polygons.size(), -1);  // -1: not yet, -2: per face
    std::vector<Vec3> whole_image;
    for (const EmittingFace& f : faces_) {
      if (!first_outline_.empty()) {
        // The whole face's image first: its clip lies in it (cheaper than clipping them all).
        whole_image.clear();
        for (const Vec3& v : f.vertices) whole_image.push_back(leg.linear * v + leg.translation);
        if (!seen_through_first(whole_image)) continue;
      }
      const std::optional<EmittingFace> clipped = clipped_to(f, leg.bounds, in_plane_);
      if (!clipped) continue;
      const Polygon& provenance = scene_.polygons[f.polygon];
      const int material = provenance.material + (last ? 0 : count_);
      int& target = unfolded_polygon[f.polygon];
      if (target == -1) {
        target = -2;
        if (convex_[f.polygon]) {
          EmittingFace outline;
          outline.vertices = provenance.vertices;
          outline.on_boundary.assign(provenance.vertices.size(), true);
          outline.normal = provenance.normal;
          if (const auto whole = clipped_to(outline, leg.bounds, in_plane_)) {
            const std::optional<EmittingFace> image = leg_copy(*whole);
            if (image && has_area(*image)) {
              target = static_cast<int>(out_.scene.polygons.size());
              out_.scene.polygons.push_back(polygon_of(*image, material, provenance));
            }
          }
        }
      }
      std::optional<EmittingFace> face = leg_copy(*clipped);
      if (!face || !has_area(*face) || !seen_through_first(face->vertices)) continue;
      if (target == -2) {
        add_face(std::move(*face), material, provenance);
        continue;
      }
      face->polygon = target;
      out_.faces.push_back(std::move(*face));
    }
  }

  /// Aperture j's outline in the image of the leg beyond it, counter-clockwise about its
  /// mapped normal.
  std::vector<Vec3> frame_outline(int j) const {
    const Leg& beyond = legs_[j + 1];
    std::vector<Vec3> o;
    for (const Vec3& v : apertures_[j].outline) o.push_back(beyond.linear * v + beyond.translation);
    if (beyond.linear.determinant() < 0) std::reverse(o.begin(), o.end());
    return o;
  }

  /// The frames: at aperture j, trapezoids from each outline edge out to a similar polygon that
  /// holds the disk of radius `reach` around the outline's centroid c. What a frame must cover
  /// lies in the convex hull of the receiver and the legs, which holds it.
  void add_frames() {
    Bounds box = out_.scene.bounds();
    for (int j = 0; j < k_; ++j) {
      for (const Vec3& v : frame_outline(j)) box.add(v);
    }
    const Bounds scene_box = scene_.bounds();  // receivers lie in it: their images in its image
    for (int corner = 0; corner < 8; ++corner) box.add(out_.receiver(corner_of(scene_box, corner)));
    for (int j = 0; j < k_; ++j) {
      const Aperture& a = apertures_[j];
      const std::vector<Vec3> o = frame_outline(j);
      const Vec3 normal = mapped_normal(legs_[j + 1].linear, a.normal);
      Vec3 c = Vec3::Zero();
      for (const Vec3& v : o) c += v;
      c /= static_cast<double>(o.size());
      double reach = 0;
      for (int corner = 0; corner < 8; ++corner)
        reach = std::max(reach, (corner_of(box, corner) - c).norm());
      reach = 2 * reach + extent(o);  // margin: the frame's far edge is seen by nothing
      double inradius = std::numeric_limits<double>::infinity();
      for (size_t i = 0; i < o.size(); ++i) {
        const Vec3 e = (o[(i + 1) % o.size()] - o[i]).normalized();
        const Vec3 r = c - o[i];
        inradius = std::min(inradius, (r - r.dot(e) * e).norm());
      }
      const double scale = reach / inradius;
      const Polygon& provenance = scene_.polygons[a.polygon];
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
        add_face(std::move(piece), frame_material(), provenance);
      }
    }
  }

  /// Corner `corner` (bits: x, y, z at the high end) of a box.
  static Vec3 corner_of(const Bounds& box, int corner) {
    return Vec3((corner & 1) ? box.hi.x() : box.lo.x(), (corner & 2) ? box.hi.y() : box.lo.y(),
                (corner & 4) ? box.hi.z() : box.lo.z());
  }

  const Scene& scene_;
  const std::vector<EmittingFace>& faces_;
  const std::vector<Aperture>& apertures_;
  const std::vector<Leg>& legs_;
  const double in_plane_;
  const std::optional<Vec3>& crossing_from_;
  const int k_;      ///< Apertures; legs are k_ + 1.
  const int count_;  ///< The scene's materials; their images follow them.
  UnfoldedScene out_;
  std::vector<char> convex_;                ///< Per scene polygon: one convex piece.
  std::vector<HalfSpace> beyond_aperture_;  ///< With a receiver: far sides of the apertures.
  std::vector<Vec3> first_outline_;         ///< With a receiver: the first aperture's image.
  Vec3 first_normal_ = Vec3::UnitZ();
};

}  // namespace

UnfoldedScene unfold_legs(const Scene& scene, const std::vector<EmittingFace>& faces,
                          const std::vector<Aperture>& apertures, const std::vector<Leg>& legs,
                          const Eigen::Matrix3d& receiver_linear, const Vec3& receiver_translation,
                          double in_plane, const std::optional<Vec3>& crossing_from) {
  return Unfolding(scene, faces, apertures, legs, in_plane, crossing_from)
      .run(receiver_linear, receiver_translation);
}

}  // namespace rad
