#include "render/albedo_render.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

namespace rad {

namespace {

template <class Shade>
Image render_primary(const RayCaster& caster, const Camera& camera, Shade shade) {
  Image image(camera.width(), camera.height());
  const Scene& scene = caster.scene();
  tbb::parallel_for(
      tbb::blocked_range<int>(0, image.height), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y) {
          for (int x = 0; x < image.width; ++x) {
            const Ray ray = camera.ray(x + 0.5, y + 0.5);
            const auto hit = caster.closest_hit(ray);
            if (!hit || !hit->front_facing) continue;  // one-sided surfaces: the back is black
            const Material& m = scene.materials[scene.polygons[hit->polygon].material];
            image.at(x, y) = m.is_emitter() ? m.emission : shade(m.reflectance, ray, *hit);
          }
        }
      });
  return image;
}

}  // namespace

Image render_albedo(const RayCaster& caster, const Camera& camera) {
  return render_primary(caster, camera, [](const Rgb& rho, const Ray&, const Hit&) { return rho; });
}

Image render_facing(const RayCaster& caster, const Camera& camera) {
  return render_primary(caster, camera, [](const Rgb& rho, const Ray& ray, const Hit& hit) -> Rgb {
    return rho * std::abs(ray.direction.dot(hit.normal));
  });
}

}  // namespace rad
