#pragma once
/// What reaches a point straight from the scene's point lights (scene/point_light.h): one
/// segment per light, through the filters on it (000 §2.2), stopped by anything opaque. The
/// path tracer and the solver take direct point light from here; the local pass decides the
/// same exactly (localpass/point_light_visibility.h).
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
