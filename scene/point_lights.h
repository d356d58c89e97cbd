#pragma once
/// What reaches a point straight from the scene's point lights (scene/point_light.h): one
/// segment per light, through the filters on it (000 §2.2), stopped by anything opaque. The
/// path tracer and the solver take direct point light from here; the local pass decides the
/// same exactly (localpass/point_light_visibility.h).
#include <vector>

#include "scene/mirror_pieces.h"
#include "scene/ray_caster.h"

namespace rad {

/// Sum over the scene's lights of I max(0, n . w) / r^2 times what the polygons on the segment
/// from x to the light pass. The segment leaves x's surface as every ray of the scene does:
/// from `offset` along n and half that back along the segment (so a polygon through x, seen
/// edge-on, hides nothing, as for the exact gatherers), and stops `offset` short of the light
/// (a light lying on a polygon is not hidden by it). Visibility is Embree's (single precision,
/// distances refined in double): exact but for points within float rounding (~1e-7 of the
/// distance) of a shadow's edge, where the irradiance jumps.
Rgb point_light_irradiance(const Scene& scene, const RayCaster& caster, const Vec3& x,
                           const Vec3& n, double offset);

/// What reaches a point from the scene's point lights straight (point_light_irradiance) and by
/// way of its perfect plane mirrors (gloss 0; glossy ones scatter lights: glossy_highlight):
/// per chain of at most Scene::mirror_depth mirror pieces (mirror_chains) and light in front
/// of its last piece, the light's image L^ = R_1 ... R_k L (paper 000 §3, the image method)
/// of intensity I times the pieces' specular reflectances, seen from x by the inverse-square
/// cosine law. Exact: a plane mirror maps the pencil of rays from L onto the one from L^, so
/// the path x -> p_1 -> ... -> p_k -> L has the length |x - L^| and arrives along x -> L^.
/// The segment to L^ must cross each piece's plane inside its outline, in order, and each leg
/// (x -> p_1, ..., p_k -> L) passes what lies on it, as for the straight segment. The solver,
/// the path tracer and the Monte Carlo gather take lights from here; the local pass unfolds
/// the same chains exactly (specular/unfolding.h).
class PointLightIrradiance {
 public:
  /// The caster's scene must outlive this; `offset` as for point_light_irradiance.
  PointLightIrradiance(const RayCaster& caster, double offset);

  /// H at x (unit normal n) from the lights, straight and by their images.
  Rgb operator()(const Vec3& x, const Vec3& n) const;

  /// The lights' images, one per chain and light in front of its last mirror.
  int image_count() const { return static_cast<int>(images_.size()); }

 private:
  struct Image {
    Vec3 position;
    Rgb intensity;           ///< The light's, times the chain's specular reflectances
    std::vector<int> chain;  ///< Pieces from x's side: x -> pieces_[chain[0]] -> ... -> light
  };
  Rgb by_image(const Image& image, const Vec3& x, const Vec3& n) const;

  const RayCaster& caster_;
  double offset_ = 0;
  double in_plane_ = 0;
  std::vector<MirrorPiece> pieces_;
  std::vector<Image> images_;
};

/// pi times the radiance a glossy surface of material m at x (unit normal n, its plane's)
/// sends in unit direction `out` from the scene's point lights (paper 003's model: the flux it
/// receives scattered by s rho(phi) per steradian, phi between `out` and the mirror direction
/// of the light's ray about the shading normal `shading`, scene/polygon.h): sum of
/// s rho(phi) I cos_in / (r^2 cos_out) through what lies between, times pi (so that it adds to
/// a radiosity). A light's highlight on a glossy surface, as the eye and the path tracer see it.
/// Through a roughened pane (glossy transmittance), the lights on the other side, the lobe
/// about their own direction, seen from either side.
Rgb glossy_highlight(const Scene& scene, const RayCaster& caster, const Material& m, const Vec3& x,
                     const Vec3& n, const Vec3& shading, const Vec3& out, double offset);

}  // namespace rad
