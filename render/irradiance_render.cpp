#include "render/irradiance_render.h"

#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <string>
#include <string_view>

#include "distributed/packed_bytes.h"
#include "scene/error.h"
#include "scene/point_lights.h"

namespace rad {

namespace {

/// Shared pixel loop: `shade(hit, weight, index, out)` adds `weight` times what a front-facing
/// hit shows to pixel `index`. The eye ray passes on through filters (000 §2.2) and roughened
/// panes (straight, their lobe's centre), and reflects off mirrors (000 §3, to the scene's
/// mirror depth; glossy ones about their lobe's centre; RayCaster::follow): each surface it meets
/// is weighted by what the filters and mirrors before it pass on, and an opaque one ends it.
/// Without filters and mirrors that is the first hit alone, as before. Over an MPI job the
/// image is cut into tiles, handed out by `job` and gathered on its root (the other processes'
/// images hold only the tiles they computed); every pixel is computed on its own, so which
/// process or thread computed it does not change a bit of it.
template <typename Shade>
IrradianceImage render_pixels(const RayCaster& caster, const Camera& camera, double gap,
                              const std::function<void(size_t)>& progress, const Job& job,
                              const Shade& shade) {
  const Scene& scene = caster.scene();
  // A roughened pane seen from its back: no radiosity (one-sided, DESIGN §3), but the point
  // lights on its front side show through its lobe (glossy_highlight, either side), apart as
  // glossy light like a highlight; the eye ray passes on through it (RayCaster::follow).
  const auto back_highlight = [&](const Hit& hit, const Rgb& weight, size_t index,
                                  IrradianceImage& out) {
    const Material& m = scene.materials[scene.polygons[hit.polygon].material];
    if (!m.is_glossy_pane()) return;
    const Rgb highlight = weight.cwiseProduct(glossy_highlight(
        scene, caster, m, hit.point, hit.normal,
        shading_normal(scene.polygons[hit.polygon], hit.point), -hit.direction, gap));
    out.radiosity.pixels[index] += highlight;
    out.glossy.pixels[index] += highlight;
  };
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
  out.interpolated.assign(count, 0);
  std::atomic<size_t> done{0};
  const auto render_range = [&](const tbb::blocked_range2d<int>& tile) {
    for (int y = tile.rows().begin(); y != tile.rows().end(); ++y) {
      for (int x = tile.cols().begin(); x != tile.cols().end(); ++x) {
        const size_t index = static_cast<size_t>(y) * width + x;
        caster.follow(camera.ray(x + 0.5, y + 0.5), RayCaster::limits_of(scene), gap,
                      [&](const Hit& hit, const Rgb& weight, int) {
                        if (!hit.front_facing) {
                          back_highlight(hit, weight, index, out);
                          return;
                        }
                        shade(hit, weight, index, out);
                        out.surface[index] = 1;
                      });
      }
    }
  };
  if (!job.distributed()) {
    tbb::parallel_for(tbb::blocked_range2d<int>(0, height, 16, 0, width, 16),
                      [&](const tbb::blocked_range2d<int>& tile) {
                        render_range(tile);
                        const size_t finished = done += tile.rows().size() * tile.cols().size();
                        if (progress) progress(finished);
                      });
    return out;
  }

  const int side = tile_side(width, height, job.size());
  const int columns = (width + side - 1) / side;
  const size_t tiles = static_cast<size_t>(columns) * ((height + side - 1) / side);
  const auto range_of = [&](size_t tile) {
    const int x0 = static_cast<int>(tile % columns) * side;
    const int y0 = static_cast<int>(tile / columns) * side;
    return tbb::blocked_range2d<int>(y0, std::min(y0 + side, height), 8, x0,
                                     std::min(x0 + side, width), 8);
  };
  const auto for_each_pixel = [&](size_t tile, const auto& f) {
    const tbb::blocked_range2d<int> r = range_of(tile);
    for (int y = r.rows().begin(); y != r.rows().end(); ++y)
      for (int x = r.cols().begin(); x != r.cols().end(); ++x)
        f(static_cast<size_t>(y) * width + x);
  };
  BlockWork work;
  work.blocks = tiles;
  work.compute = [&](size_t tile) { tbb::parallel_for(range_of(tile), render_range); };
  work.pack = [&](size_t tile) {
    PackedBytes bytes;
    for_each_pixel(tile, [&](size_t i) {
      for (const Image* image : {&out.radiosity, &out.refracted, &out.glossy, &out.bound})
        bytes.put_each(image->pixels[i]);
      bytes.put(out.gathered_exactly[i]);
      bytes.put(out.projected[i]);
      bytes.put(out.clusters[i]);
      bytes.put(out.surface[i]);
      bytes.put(out.interpolated[i]);
    });
    return bytes.take();
  };
  work.unpack = [&](size_t tile, std::string_view data) {
    PackedBytes bytes(data);
    for_each_pixel(tile, [&](size_t i) {
      for (Image* image : {&out.radiosity, &out.refracted, &out.glossy, &out.bound})
        bytes.get_each(image->pixels[i]);
      bytes.get(out.gathered_exactly[i]);
      bytes.get(out.projected[i]);
      bytes.get(out.clusters[i]);
      bytes.get(out.surface[i]);
      bytes.get(out.interpolated[i]);
    });
    if (!bytes.at_end()) throw Error("render: a tile came back with the wrong size");
  };
  const size_t tile_pixels = static_cast<size_t>(side) * side;
  work.progress = [&](size_t blocks) {
    if (progress) progress(std::min(count, blocks * tile_pixels));
  };
  job.run_blocks(work);
  return out;
}

/// The interpolation cells' results, gathered before the pixel loop: per pixel, its local
/// pass result when `has` it (a pixel seeing one polygon directly, in a cell that could be
/// gathered by LocalPass::gather_tile, or on a cell's corner).
struct CellResults {
  std::vector<LocalPassResult> result;
  std::vector<char> has;
  size_t count = 0;  ///< pixels that have one
};

CellResults gather_cells(const RayCaster& caster, const Camera& camera, const LocalPass& pass,
                         double tolerance, double gap,
                         const std::function<void(size_t)>& progress) {
  const Scene& scene = caster.scene();
  const int width = camera.width(), height = camera.height(), side = pass.tile();
  const size_t count = static_cast<size_t>(width) * height;
  CellResults cells;
  cells.result.resize(count);
  cells.has.assign(count, 0);
  // What each pixel sees: one front-facing polygon, directly (one visit of weight 1), or -1.
  std::vector<int> polygon(count, -1);
  std::vector<Vec3> point(count), normal(count);
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y) {
      for (int x = 0; x < width; ++x) {
        const size_t i = static_cast<size_t>(y) * width + x;
        int visits = 0;
        caster.follow(camera.ray(x + 0.5, y + 0.5), RayCaster::limits_of(scene), gap,
                      [&](const Hit& hit, const Rgb& weight, int) {
                        if (++visits == 1 && hit.front_facing && weight == Rgb::Ones()) {
                          polygon[i] = hit.polygon, point[i] = hit.point, normal[i] = hit.normal;
                        }
                      });
        if (visits != 1) polygon[i] = -1;
      }
    }
  });
  // The corner lines: every side-th row and column, and the last.
  const auto lines = [&](int extent) {
    std::vector<int> at;
    for (int v = 0; v < extent; v += side) at.push_back(v);
    if (at.back() != extent - 1) at.push_back(extent - 1);
    return at;
  };
  const std::vector<int> xs = lines(width), ys = lines(height);
  if (xs.size() < 2 || ys.size() < 2) return cells;
  const auto index = [&](int x, int y) { return static_cast<size_t>(y) * width + x; };
  tbb::parallel_for(size_t{0}, xs.size() * ys.size(), [&](size_t k) {
    const size_t i = index(xs[k % xs.size()], ys[k / xs.size()]);
    if (polygon[i] < 0) return;
    cells.result[i] = pass.gather(point[i], normal[i], tolerance);
    cells.has[i] = 1;
  });
  std::atomic<size_t> done{0};
  const size_t columns = xs.size() - 1, rows = ys.size() - 1;
  tbb::parallel_for(size_t{0}, columns * rows, [&](size_t k) {
    const size_t cx = k % columns, cy = k / columns;
    // The cell's pixels: its corner lines' pixels to the left and top are its own, and the
    // last cell's right and bottom lines too; corners are gathered already.
    const int x0 = xs[cx], x1 = xs[cx + 1], y0 = ys[cy], y1 = ys[cy + 1];
    const int x_end = cx + 1 == columns ? x1 : x1 - 1, y_end = cy + 1 == rows ? y1 : y1 - 1;
    const std::array<size_t, 4> corner = {index(x0, y0), index(x1, y0), index(x1, y1),
                                          index(x0, y1)};
    const int seen = polygon[corner[0]];
    std::vector<size_t> members;
    std::vector<Vec3> points;
    bool whole = seen >= 0;
    for (int y = y0; y <= y_end && whole; ++y) {
      for (int x = x0; x <= x_end && whole; ++x) {
        const size_t i = index(x, y);
        whole = polygon[i] == seen && normal[i] == normal[corner[0]];
        if (cells.has[i] || !whole) continue;
        members.push_back(i);
        points.push_back(point[i]);
      }
    }
    for (const size_t c : corner)
      whole = whole && polygon[c] == seen && normal[c] == normal[corner[0]];
    if (!whole || members.empty()) return;
    const std::array<Vec3, 4> corners = {point[corner[0]], point[corner[1]], point[corner[2]],
                                         point[corner[3]]};
    const std::array<LocalPassResult, 4> at_corners = {
        cells.result[corner[0]], cells.result[corner[1]], cells.result[corner[2]],
        cells.result[corner[3]]};
    const std::vector<LocalPassResult> results =
        pass.gather_tile(corners, at_corners, points, normal[corner[0]], tolerance);
    for (size_t m = 0; m < members.size(); ++m) {
      cells.result[members[m]] = results[m];
      cells.has[members[m]] = 1;
    }
    const size_t finished = done += members.size();
    if (progress) progress(finished);
  });
  cells.count = static_cast<size_t>(std::ranges::count(cells.has, 1));
  return cells;
}

}  // namespace

IrradianceImage render_local_pass(const Scene& scene, const RayCaster& caster, const Camera& camera,
                                  const LocalPass& pass, double tolerance,
                                  const std::function<void(size_t)>& progress, const Job& job) {
  // Through filters and mirrors the pixel is sum_k w_k B_k with w_k >= 0 known exactly, so the
  // weighted sum of the points' certified bounds bounds its error. (The tolerance applies to
  // each point's H, as without them: a pixel's bound relative to its B can exceed it where rho
  // or the weights differ between channels.)
  const double offset = scene.tolerance().ray_offset;  // O(polygons): once, not per pixel
  // The cells first (their pixels seeing one polygon directly: the loop below visits each of
  // them once, with that hit), then every pixel, gathering those without a result.
  CellResults cells;
  const size_t count = static_cast<size_t>(camera.width()) * camera.height();
  const bool tiled = pass.tile() > 1 && tolerance > 0 && !job.distributed() && pass.interpolates();
  if (tiled) cells = gather_cells(caster, camera, pass, tolerance, offset, progress);
  const auto rest_progress = [&](size_t done) {
    if (progress) progress(cells.count + done * (count - cells.count) / std::max<size_t>(count, 1));
  };
  return render_pixels(
      caster, camera, offset, tiled ? std::function<void(size_t)>(rest_progress) : progress, job,
      [&](const Hit& hit, const Rgb& weight, size_t index, IrradianceImage& out) {
        const Material& material = scene.materials[scene.polygons[hit.polygon].material];
        const LocalPassResult r = tiled && cells.has[index]
                                      ? cells.result[index]
                                      : pass.gather(hit.point, hit.normal, tolerance);
        out.interpolated[index] = static_cast<char>(r.interpolated);
        out.radiosity.pixels[index] +=
            weight.cwiseProduct(material.emission + material.reflectance.cwiseProduct(
                                                        r.irradiance + r.refracted + r.glossy));
        out.refracted.pixels[index] +=
            weight.cwiseProduct(material.reflectance.cwiseProduct(r.refracted));
        // A point light's highlight on a glossy surface (003's lobe), apart as glossy light.
        const Rgb highlight = glossy_highlight(
            scene, caster, material, hit.point, hit.normal,
            shading_normal(scene.polygons[hit.polygon], hit.point), -hit.direction, offset);
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
                                   int samples, const std::function<void(size_t)>& progress,
                                   const Job& job) {
  const double offset = scene.tolerance().ray_offset;  // O(polygons): once, not per pixel
  IrradianceImage image = render_pixels(
      caster, camera, offset, progress, job,
      [&](const Hit& hit, const Rgb& weight, size_t index, IrradianceImage& out) {
        const Material& material = scene.materials[scene.polygons[hit.polygon].material];
        const Rgb h = gatherer.gather(hit.point, hit.normal, samples, index);
        const Rgb highlight = glossy_highlight(
            scene, caster, material, hit.point, hit.normal,
            shading_normal(scene.polygons[hit.polygon], hit.point), -hit.direction, offset);
        out.radiosity.pixels[index] += weight.cwiseProduct(
            material.emission + material.reflectance.cwiseProduct(h) + highlight);
      });
  image.samples_per_pixel = samples;
  return image;
}

IrradianceImage render_path_traced(const Scene& scene, const RayCaster& caster,
                                   const Camera& camera, const PathTracer& tracer, int paths,
                                   const std::function<void(size_t)>& progress, const Job& job) {
  const double offset = scene.tolerance().ray_offset;  // O(polygons): once, not per pixel
  IrradianceImage image = render_pixels(
      caster, camera, offset, progress, job,
      [&](const Hit& hit, const Rgb& weight, size_t index, IrradianceImage& out) {
        const Material& material = scene.materials[scene.polygons[hit.polygon].material];
        out.radiosity.pixels[index] += weight.cwiseProduct(glossy_highlight(
            scene, caster, material, hit.point, hit.normal,
            shading_normal(scene.polygons[hit.polygon], hit.point), -hit.direction, offset));
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

int tile_side(int width, int height, int processes) {
  int side = 64;
  const auto tiles = [&](int s) {
    return static_cast<long>((width + s - 1) / s) * ((height + s - 1) / s);
  };
  while (side > 16 && tiles(side) < 8L * processes) side /= 2;
  return side;
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
    if (!image.interpolated.empty()) s.interpolated += image.interpolated[i];
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
