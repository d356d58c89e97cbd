#pragma once
/// The simplest per-pixel pass: what the primary ray sees, with no lighting at all. It checks
/// the scene, the camera and the ray caster end to end, and shows the geometry quickly.
#include "formats/image.h"
#include "scene/camera.h"
#include "scene/ray_caster.h"

namespace rad {

/// Per pixel, one ray through the pixel centre: the front side of a surface shows its
/// reflectance, an emitter's front shows its emission (exitance, W/m^2); back sides and misses
/// are black. Parallel over rows (TBB); the result does not depend on the thread count.
Image render_albedo(const RayCaster& caster, const Camera& camera);

/// Like render_albedo, with non-emitters scaled by |cos| of the angle between the view ray and
/// the surface normal ("headlight" shading), so faces of equal reflectance stay distinguishable.
Image render_facing(const RayCaster& caster, const Camera& camera);

}  // namespace rad
