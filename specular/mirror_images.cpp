#include "specular/mirror_images.h"

#include <algorithm>
#include <cmath>

#include "scene/polygon.h"
#include "scene/polygon_faces.h"

namespace rad {
namespace {

/// The front half-space of a mirror piece: where it reflects.
HalfSpace front_of(const MirrorPiece& m) { return {m.normal, m.offset}; }

}  // namespace

UnfoldedScene unfold(const Scene& scene, const std::vector<EmittingFace>& faces,
                     const std::vector<MirrorPiece>& pieces, const std::vector<int>& chain,
                     double in_plane) {
  // Leg j (1-based, k + 1 the last) lies in front of m_(j-1) and m_j and is mapped by
  // T_j = R_k ... R_j (T_(k+1) the identity): the receiver is mapped by T_1, the last leg
  // stays where it is.
  const int k = static_cast<int>(chain.size());
  std::vector<Leg> legs(k + 1);
  std::vector<Aperture> apertures;
  Rgb specular = Rgb::Ones();
  for (int j = k; j >= 1; --j) {
    // T_j = T_(j+1) R_j, with R_j(p) = (I - 2 n n^T) p + 2 offset n.
    const MirrorPiece& m = pieces[chain[j - 1]];
    const Eigen::Matrix3d reflection =
        Eigen::Matrix3d::Identity() - 2 * m.normal * m.normal.transpose();
    const Leg& after = legs[j];
    legs[j - 1].linear = after.linear * reflection;
    legs[j - 1].translation = after.linear * (2 * m.offset * m.normal) + after.translation;
    specular = specular.cwiseProduct(m.specular);
  }
  for (int j = 1; j <= k + 1; ++j) {
    if (j >= 2) legs[j - 1].bounds.push_back(front_of(pieces[chain[j - 2]]));
    if (j <= k) legs[j - 1].bounds.push_back(front_of(pieces[chain[j - 1]]));
  }
  for (const int piece : chain) {
    const MirrorPiece& m = pieces[piece];
    apertures.push_back({m.outline, m.normal, m.polygon});
  }
  UnfoldedScene out =
      unfold_legs(scene, faces, apertures, legs, legs[0].linear, legs[0].translation, in_plane);
  out.specular = specular;
  return out;
}

Eigen::AlignedBox3d sources_in_front(const std::vector<EmittingFace>& faces,
                                     const std::vector<MirrorPiece>& pieces,
                                     const std::vector<PointLight>& lights,
                                     const MirrorPiece& mirror, double in_plane) {
  Eigen::AlignedBox3d box;
  const std::vector<HalfSpace> front{front_of(mirror)};
  for (const PointLight& light : lights) {
    if (front.front().height(light.position) > in_plane) box.extend(light.position);
  }
  for (const EmittingFace& f : faces) {
    if (f.exitance == Rgb::Zero()) continue;
    if (const auto clipped = clipped_to(f, front, in_plane)) {
      for (const Vec3& v : clipped->vertices) box.extend(v);
    }
  }
  for (const MirrorPiece& p : pieces) {
    EmittingFace outline;
    outline.vertices = p.outline;
    outline.on_boundary.assign(p.outline.size(), true);
    outline.normal = p.normal;
    if (const auto clipped = clipped_to(outline, front, in_plane)) {
      for (const Vec3& v : clipped->vertices) box.extend(v);
    }
  }
  return box;
}

bool may_see_through(const MirrorPiece& mirror, const Vec3& x_mirrored,
                     const Eigen::AlignedBox3d& sources) {
  if (sources.isEmpty()) return false;
  if (!(mirror.height(x_mirrored) < 0)) return true;  // not behind the plane: no claim
  std::vector<Vec3> corners;
  for (int corner = 0; corner < 8; ++corner)
    corners.push_back(sources.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)));
  return may_show_through(mirror.outline, mirror.normal, x_mirrored, corners);
}

}  // namespace rad
