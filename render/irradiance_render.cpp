#include "render/irradiance_render.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>

namespace rad {

namespace {

/// Shared pixel loop: `shade(hit, index, out)` fills pixel `index` of a front-facing hit.
template <typename Shade>
IrradianceImage render_pixels(const RayCaster& caster, const Camera& camera,
                              const std::function<void(size_t)>& progress, const Shade& shade) {
  const int width = camera.width(), height = camera.height();
  IrradianceImage out;
  out.radiosity = Image(width, height);
  out.bound = Image(width, height);
  const size_t count = static_cast<size_t>(width) * height;
  out.gathered_exactly.assign(count, 0);
  out.projected.assign(count, 0);
  out.clusters.assign(count, 0);
  out.surface.assign(count, 0);
  std::atomic<size_t> done{0};
  tbb::parallel_for(tbb::blocked_range2d<int>(0, height, 16, 0, width, 16),
                    [&](const tbb::blocked_range2d<int>& tile) {
                      for (int y = tile.rows().begin(); y != tile.rows().end(); ++y) {
                        for (int x = tile.cols().begin(); x != tile.cols().end(); ++x) {
                          const size_t index = static_cast<size_t>(y) * width + x;
                          const auto hit = caster.closest_hit(camera.ray(x + 0.5, y + 0.5));
                          if (!hit || !hit->front_facing) continue;
                          shade(*hit, index, out);
                          out.surface[index] = 1;
                        }
                      }
                      const size_t finished = done += tile.rows().size() * tile.cols().size();
                      if (progress) progress(finished);
                    });
  return out;
}

}  // namespace

IrradianceImage render_local_pass(const Scene& scene, const RayCaster& caster, const Camera& camera,
                                  const LocalPass& pass, double tolerance,
                                  const std::function<void(size_t)>& progress) {
  return render_pixels(
      caster, camera, progress, [&](const Hit& hit, size_t index, IrradianceImage& out) {
        const Material& material = scene.materials[scene.polygons[hit.polygon].material];
        const LocalPassResult r = pass.gather(hit.point, hit.normal, tolerance);
        out.radiosity.pixels[index] =
            material.emission + material.reflectance.cwiseProduct(r.irradiance);
        out.bound.pixels[index] = material.reflectance.cwiseProduct(r.bound);
        out.gathered_exactly[index] = r.gathered_exactly;
        out.projected[index] = r.projected;
        out.clusters[index] = r.clusters;
      });
}

IrradianceImage render_monte_carlo(const Scene& scene, const RayCaster& caster,
                                   const Camera& camera, const MonteCarloGatherer& gatherer,
                                   int samples, const std::function<void(size_t)>& progress) {
  IrradianceImage image = render_pixels(
      caster, camera, progress, [&](const Hit& hit, size_t index, IrradianceImage& out) {
        const Material& material = scene.materials[scene.polygons[hit.polygon].material];
        const Rgb h = gatherer.gather(hit.point, hit.normal, samples, index);
        out.radiosity.pixels[index] = material.emission + material.reflectance.cwiseProduct(h);
      });
  image.samples_per_pixel = samples;
  return image;
}

IrradianceSummary summarize(const IrradianceImage& image) {
  IrradianceSummary s;
  double gathered_sum = 0, projected_sum = 0, clusters_sum = 0, relative_bound_sum = 0;
  for (size_t i = 0; i < image.surface.size(); ++i) {
    if (!image.surface[i]) continue;
    ++s.pixels;
    gathered_sum += image.gathered_exactly[i];
    projected_sum += image.projected[i];
    if (!image.clusters.empty()) clusters_sum += image.clusters[i];
    s.gathered_exactly_max = std::max(s.gathered_exactly_max, image.gathered_exactly[i]);
    s.projected_max = std::max(s.projected_max, image.projected[i]);
    const double bound = image.bound.pixels[i].maxCoeff();
    const double value = image.radiosity.pixels[i].maxCoeff();
    s.bound_max = std::max(s.bound_max, bound);
    const double relative = value > 0 ? bound / value : 0;
    relative_bound_sum += relative;
    s.relative_bound_max = std::max(s.relative_bound_max, relative);
  }
  const double n = static_cast<double>(std::max<size_t>(s.pixels, 1));
  s.gathered_exactly_mean = gathered_sum / n;
  s.projected_mean = projected_sum / n;
  s.clusters_mean = clusters_sum / n;
  s.relative_bound_mean = relative_bound_sum / n;
  return s;
}

}  // namespace rad
