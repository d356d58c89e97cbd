#include "scene/mirror_pieces.h"

#include <algorithm>

#include "scene/polygon_faces.h"

namespace rad {

std::vector<MirrorPiece> mirror_pieces(const Scene& scene) {
  std::vector<MirrorPiece> pieces;
  for (const EmittingFace& f : faces_from_polygons(scene)) {
    const Material& m = scene.materials[scene.polygons[f.polygon].material];
    if (!m.is_mirror()) continue;
    pieces.push_back(
        {f.polygon, f.vertices, f.normal, f.normal.dot(f.vertices.front()), m.specular});
  }
  return pieces;
}

std::vector<std::vector<int>> mirror_chains(const std::vector<MirrorPiece>& pieces, int depth,
                                            double in_plane) {
  // b can follow a: they are in different planes, and each has a vertex in front of the other.
  const auto faces_towards = [&](const MirrorPiece& a, const MirrorPiece& b) {
    for (const Vec3& v : b.outline) {
      if (a.height(v) > in_plane) return true;
    }
    return false;
  };
  const auto can_follow = [&](int a, int b) {
    return a != b && faces_towards(pieces[a], pieces[b]) && faces_towards(pieces[b], pieces[a]);
  };
  std::vector<std::vector<int>> chains, level;
  for (int i = 0; i < static_cast<int>(pieces.size()); ++i) level.push_back({i});
  for (int k = 1; k <= depth && !level.empty(); ++k) {
    chains.insert(chains.end(), level.begin(), level.end());
    std::vector<std::vector<int>> next;
    for (const std::vector<int>& chain : level) {
      for (int i = 0; i < static_cast<int>(pieces.size()); ++i) {
        if (!can_follow(chain.back(), i)) continue;
        next.push_back(chain);
        next.back().push_back(i);
      }
    }
    level = std::move(next);
  }
  std::sort(chains.begin(), chains.end());
  return chains;
}

}  // namespace rad
