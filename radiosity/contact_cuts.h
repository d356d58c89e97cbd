#pragma once
/// Cutting polygons along their contact lines before they are meshed.
#include <vector>

#include "geometry/vec.h"
#include "scene/scene.h"

namespace rad {

/// The convex pieces of scene polygon `index` (counter-clockwise from its front, in its plane),
/// cut along every segment where another polygon rises from its front: the foot of a block
/// standing on a floor, a wall passing through it. Radiosity jumps there, from lit to buried or
/// to a contact shadow (Heckbert 1992's D0 discontinuities; Lischinski, Tampieri, Greenberg
/// 1992), and a patch or element straddling the line would average the two sides: its live
/// part is then too dark wherever it shoots, and too bright or too dark where a point near the
/// contact gathers from it. Each segment cuts the pieces it crosses along the line through it
/// (a convex piece is cut only by chords). Segments on the polygon's outline, and polygons
/// behind it or in its plane, cut nothing. Empty when nothing cuts the polygon. At most `max_cuts`
/// segments are used, the longest first. With `near` (built once for the scene), only the
/// polygons it lists are looked at, with the same result: a scene of 50,000 polygons is cut in
/// seconds rather than the hour that testing every pair would take.
class NearPolygons;
std::vector<std::vector<Vec3>> contact_pieces(const Scene& scene, int index, int max_cuts = 64,
                                              const NearPolygons* near = nullptr);

/// The scene's polygons by a uniform grid over their bounding boxes: which polygons' boxes,
/// grown by the scene's pad, can meet a polygon's.
class NearPolygons {
 public:
  explicit NearPolygons(const Scene& scene);
  /// Every polygon whose grown box meets polygon `index`'s (itself included), in increasing
  /// order; a superset of those that do (whole grid cells are taken).
  std::vector<int> of(int index) const;
  double pad() const { return pad_; }

 private:
  int cell(int x, int y, int z) const { return (z * cells_[1] + y) * cells_[0] + x; }
  /// The cells a polygon's grown box covers, as [low, high] per axis.
  void cell_range(int index, int low[3], int high[3]) const;
  const Scene& scene_;
  double pad_;
  Vec3 origin_, size_;  ///< Of a cell
  int cells_[3] = {1, 1, 1};
  std::vector<std::vector<int>> members_;  ///< Per cell: the polygons whose grown box meets it
};

}  // namespace rad
