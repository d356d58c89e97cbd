#include "render/irradiance_render.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>

#include "scene/point_lights.h"

namespace rad {

namespace {

/// Shared pixel loop: `shade(hit, weight, index, out)` adds `weight` times what a front-facing
/// hit shows to pixel `index`. The eye ray passes on through filters (000 §2.2) and reflects
/// off mirrors (000 §3, to the scene's mirror depth; RayCaster::follow): each surface it meets
/// is weighted by what the filters and mirrors before it pass on, and an opaque one ends it.
/// Without filters and mirrors that is the first hit alone, as before.
template <typename Shade>
IrradianceImage render_pixels(const RayCaster& caster, const Camera& camera, double gap,
                              const std::function<void(size_t)>& progress, const Shade& shade) {
  const Scene& scene = caster.scene();
  const int width = camera.width(), height = camera.height();
  IrradianceImage out;
  out.radiosity = Image(width, height);
  out.bound = Image(width, height);
  out.refracted = Image(width, height);
  out.glossy = Image(width, height);
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
                          caster.follow(camera.ray(x + 0.5, y + 0.5), RayCaster::limits_of(scene),
                                        gap, [&](const Hit& hit, const Rgb& weight, int) {
                                          if (!hit.front_facing) return;
                                          shade(hit, weight, index, out);
                                          out.surface[index] = 1;
                                        });
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
  // Through filters and mirrors the pixel is sum_k w_k B_k with w_k >= 0 known exactly, so the
  // weighted sum of the points' certified bounds bounds its error. (The tolerance applies to
  // each point's H, as without them: a pixel's bound relative to its B can exceed it where rho
  // or the weights differ between channels.)
  return render_pixels(
      caster, camera, scene.tolerance().ray_offset, progress,
      [&](const Hit& hit, const Rgb& weight, size_t index, IrradianceImage& out) {
        const Material& material = scene.materials[scene.polygons[hit.polygon].material];
        const LocalPassResult r = pass.gather(hit.point, hit.normal, tolerance);
        out.radiosity.pixels[index] +=
            weight.cwiseProduct(material.emission + material.reflectance.cwiseProduct(
                                                        r.irradiance + r.refracted + r.glossy));
        out.refracted.pixels[index] +=
            weight.cwiseProduct(material.reflectance.cwiseProduct(r.refracted));
        // A point light's highlight on a glossy surface (003's lobe), apart as glossy light.
        const Rgb highlight =
            glossy_highlight(scene, caster, material, hit.point, hit.normal,
                             shading_normal(scene.polygons[hit.polygon], hit.point), -hit.direction,
                             scene.tolerance().ray_offset);
        out.radiosity.pixels[index] += weight.cwiseProduct(highlight);
        out.glossy.pixels[index] +=
            weight.cwiseProduct(material.reflectance.cwiseProduct(r.glossy) + highlight);
        out.bound.pixels[index] += weight.cwiseProduct(material.reflectance.cwiseProduct(r.bound));
        out.gathered_exactly[index] += r.gathered_exactly;
        out.projected[index] += r.projected;
        out.clusters[index] += r.clusters;
      });
}

IrradianceImage render_monte_carlo(const Scene& scene, const RayCaster& caster,
                                   const Camera& camera, const MonteCarloGatherer& gatherer,
                                   int samples, const std::function<void(size_t)>& progress) {
  IrradianceImage image = render_pixels(
      caster, camera, scene.tolerance().ray_offset, progress,
      [&](const Hit& hit, const Rgb& weight, size_t index, IrradianceImage& out) {
        const Material& material = scene.materials[scene.polygons[hit.polygon].material];
        const Rgb h = gatherer.gather(hit.point, hit.normal, samples, index);
        const Rgb highlight =
            glossy_highlight(scene, caster, material, hit.point, hit.normal,
                             shading_normal(scene.polygons[hit.polygon], hit.point), -hit.direction,
                             scene.tolerance().ray_offset);
        out.radiosity.pixels[index] += weight.cwiseProduct(
            material.emission + material.reflectance.cwiseProduct(h) + highlight);
      });
  image.samples_per_pixel = samples;
  return image;
}

IrradianceImage render_path_traced(const Scene& scene, const RayCaster& caster,
                                   const Camera& camera, const PathTracer& tracer, int paths,
                                   const std::function<void(size_t)>& progress) {
  IrradianceImage image = render_pixels(
      caster, camera, scene.tolerance().ray_offset, progress,
      [&](const Hit& hit, const Rgb& weight, size_t index, IrradianceImage& out) {
        const Material& material = scene.materials[scene.polygons[hit.polygon].material];
        out.radiosity.pixels[index] += weight.cwiseProduct(
            glossy_highlight(scene, caster, material, hit.point, hit.normal,
                             shading_normal(scene.polygons[hit.polygon], hit.point), -hit.direction,
                             scene.tolerance().ray_offset));
        if (material.reflectance == Rgb::Zero()) {
          out.radiosity.pixels[index] += weight.cwiseProduct(material.emission);
          return;
        }
        const Rgb h = tracer.irradiance(hit.point, hit.normal, paths, index).mean;
        out.radiosity.pixels[index] +=
            weight.cwiseProduct(material.emission + material.reflectance.cwiseProduct(h));
      });
  image.samples_per_pixel = paths;
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
    // Relative to the certified part: the heuristic parts are not covered (000 §4, 003).
    const double bound = image.bound.pixels[i].maxCoeff();
    const double value = image.certified_part(i).maxCoeff();
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
