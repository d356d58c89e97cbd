#pragma once
/// The classic radiosity display: Gouraud-interpolated element radiosities at the primary hit.
/// This is the baseline the exact local pass must beat.
#include "formats/image.h"
#include "radiosity/solution.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace rad {

/// Per pixel, one primary ray through the pixel centre against the solution's element mesh; the
/// value is the mean-value interpolation of the element's vertex radiosities (area-weighted
/// means of the elements around each vertex), + rho * ambient when `with_ambient` (Cohen et al.
/// 1988). Back sides and misses are black. Radiosity B [W/m^2]; divide by pi for radiance.
/// Parallel over rows (TBB), independent of the thread count.
Image render_patches(const Scene& scene, const Solution& solution, const Camera& camera,
                     bool with_ambient);

}  // namespace rad
