// `radiosity render SCENE [--solution S.vtp] --method hemisphere|vertex|patches|albedo|facing
// [--tolerance T] -o IMAGE.exr`: per-pixel images from the scene camera; the exact methods run
// the error-bounded local pass and write a stats JSON next to the image.
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "cli/commands.h"
#include "cli/common.h"
#include "cli/inputs.h"
#include "cli/methods.h"
#include "distributed/job.h"
#include "formats/atomic_file.h"
#include "formats/image_io.h"
#include "formats/render_stats.h"
#include "formats/solution_io.h"
#include "radiosity/solution_faces.h"
#include "reference/path_tracer.h"
#include "render/albedo_render.h"
#include "render/irradiance_render.h"
#include "render/patch_render.h"
#include "scene/error.h"
#include "scene/ray_caster.h"

namespace rad::cli {
namespace {

struct RenderOptions {
  std::string scene;
  bool no_mirror_culling = false;
  LocalPassSettings settings;  ///< The refraction knob
  std::string method = "hemisphere";
  std::string solution;  ///< .vtp from `solve`, for methods that need one
  double tolerance = 0.1;
  int samples = 64;   ///< montecarlo: rays per pixel
  std::string stats;  ///< JSON path; default: the output with extension .stats.json
  bool no_ambient = false;
  std::string output;
  std::string preview;  ///< PNG path; default: the output with extension .png
  bool no_preview = false;
  int width = 0, height = 0;       ///< 0: the scene camera's
  std::optional<double> exposure;  ///< stops; none: auto_exposure of the image
  int threads = 0;                 ///< 0: all cores
};

/// Per-pixel statistics of a local-pass render, as written to the stats JSON.
RenderStats local_pass_stats(const RenderOptions& o, const IrradianceImage& image, int face_count,
                             int leaves, double seconds) {
  IrradianceSummary summary = summarize(image);
  if (image.samples_per_pixel > 0) {
    // Monte Carlo: the file has always reported the rays per pixel in these fields.
    summary.gathered_exactly_mean = summary.projected_mean = image.samples_per_pixel;
    summary.gathered_exactly_max = summary.projected_max = image.samples_per_pixel;
  }
  RenderStats out;
  out.method = o.method;
  if (image.samples_per_pixel > 0) {
    out.samples = o.samples;
  } else {
    out.tolerance = o.tolerance;
  }
  out.width = image.radiosity.width;
  out.height = image.radiosity.height;
  out.seconds = seconds;
  // A process's threads: what -j allows (the task arena reports the machine's cores).
  out.threads = static_cast<int>(
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  out.processes = Job::world().size();
  out.faces = face_count;
  out.octree_leaves = leaves;
  out.pixels_gathered = summary.pixels;
  out.pixels_interpolated = summary.interpolated;
  if (image.samples_per_pixel == 0) out.tile = o.settings.tile;
  out.emitting_mean = summary.gathered_exactly_mean;
  out.emitting_max = summary.gathered_exactly_max;
  out.projected_mean = summary.projected_mean;
  out.projected_max = summary.projected_max;
  out.clusters_mean = summary.clusters_mean;
  out.relative_bound_mean = summary.relative_bound_mean;
  out.relative_bound_max = summary.relative_bound_max;
  out.bound_max = summary.bound_max;
  // The heuristic parts (000 §4's refraction, 003's glossy beams), apart from the bound (which
  // covers the rest).
  double total_sum = 0;
  for (const Rgb& b : image.radiosity.pixels) total_sum += b.sum();
  for (const auto& [name, part] : image.heuristic_parts()) {
    size_t pixels = 0;
    double sum = 0;
    for (const Rgb& r : part->pixels) pixels += r.sum() > 0, sum += r.sum();
    if (pixels == 0) continue;
    out.heuristic_parts.push_back({name, pixels, total_sum > 0 ? sum / total_sum : 0.0});
  }
  return out;
}

/// Per-pixel statistics for `export --stats`: faces projected and gathered (rays, for Monte
/// Carlo), 1 where a front-facing surface was gathered, and for the exact methods the
/// certified bound on B (largest channel), the bound relative to B, and 1 where a cell
/// interpolated the pixel's smooth part (localpass/tile_gather.h).
ChannelImage pixel_channels(const IrradianceImage& image, bool certified) {
  ChannelImage out{image.radiosity.width, image.radiosity.height, {}};
  const size_t n = image.surface.size();
  auto& projected = out.channels["projected"];
  auto& emitting = out.channels["emitting"];
  auto& surface = out.channels["surface"];
  for (auto* c : {&projected, &emitting, &surface}) c->resize(n);
  for (size_t i = 0; i < n; ++i) {
    // Monte Carlo: the rays per pixel, as the file has always reported.
    const int samples = image.surface[i] ? image.samples_per_pixel : 0;
    projected[i] = static_cast<float>(image.samples_per_pixel > 0 ? samples : image.projected[i]);
    emitting[i] =
        static_cast<float>(image.samples_per_pixel > 0 ? samples : image.gathered_exactly[i]);
    surface[i] = image.surface[i] ? 1.0f : 0.0f;
  }
  if (!certified) return out;
  auto& bound = out.channels["bound"];
  auto& relative = out.channels["relative_bound"];
  auto& interpolated = out.channels["interpolated"];
  bound.resize(n);
  relative.resize(n);
  interpolated.resize(n);
  for (size_t i = 0; i < n; ++i) {
    interpolated[i] = image.interpolated[i] ? 1.0f : 0.0f;
    // The bound covers the certified part alone: B less the heuristic parts (000 §4, 003).
    const double b = image.bound.pixels[i].maxCoeff();
    const double value = image.certified_part(i).maxCoeff();
    bound[i] = static_cast<float>(b);
    relative[i] = value > 0 ? static_cast<float>(b / value) : 0.0f;
  }
  // Each heuristic part that lights anything, as a channel of its own (largest channel).
  for (const auto& [name, part] : image.heuristic_parts()) {
    bool any = false;
    for (const Rgb& r : part->pixels) any = any || r != Rgb::Zero();
    if (!any) continue;
    std::vector<float>& channel = out.channels[name];
    channel.resize(n);
    for (size_t i = 0; i < n; ++i) channel[i] = static_cast<float>(part->pixels[i].maxCoeff());
  }
  return out;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// What a render made: the image, and for the local pass its statistics and per-pixel channels.
struct Rendered {
  Image image;
  std::optional<RenderStats> stats;
  ChannelImage pixel_stats;
};

/// A progress bar's callback over the pixels of a camera's image.
std::function<void(size_t)> pixel_progress(ProgressBar& bar, const CameraSpec& spec) {
  const double total = static_cast<double>(spec.width) * spec.height;
  return [&bar, total](size_t done) { bar.update(done / total, std::to_string(done) + " pixels"); };
}

/// The local pass (004 Fig. 6) or Monte Carlo over the solution's elements, split over the
/// job's processes. Nothing on a process other than the root (its image holds only its tiles).
std::optional<Rendered> render_from_solution(const RenderOptions& o, const MethodTraits& m,
                                             const Inputs& inputs, const CameraSpec& spec,
                                             const Job& job,
                                             std::chrono::steady_clock::time_point start) {
  const Scene& scene = inputs.scene;
  const Solution& solution = *inputs.solution;
  std::vector<EmittingFace> faces;
  std::optional<RayCaster> caster;
  std::optional<LocalPass> pass;
  std::optional<MonteCarloGatherer> monte_carlo;
  job.step([&] {
    faces = faces_from_solution(scene, solution);
    caster.emplace(scene);
    if (!m.exact) {
      monte_carlo.emplace(scene, faces);
    } else {
      LocalPassSettings settings = o.settings;
      settings.mirror_culling = !o.no_mirror_culling;
      pass.emplace(scene, faces, *m.local, settings);
    }
  });
  const Camera camera(spec);
  ProgressBar bar("render");
  const auto progress = pixel_progress(bar, spec);
  const IrradianceImage result =
      pass ? render_local_pass(scene, *caster, camera, *pass, o.tolerance, progress, job)
           : render_monte_carlo(scene, *caster, camera, *monte_carlo, o.samples, progress, job);
  bar.finish();
  if (!job.is_root()) return std::nullopt;
  const int leaves = pass ? static_cast<int>(pass->octree().leaves().size()) : 0;
  return Rendered{
      result.radiosity,
      local_pass_stats(o, result, static_cast<int>(faces.size()), leaves, seconds_since(start)),
      pixel_channels(result, m.exact)};
}

/// The reference: the scene path-traced, split over the job's processes; nothing off the root.
std::optional<Rendered> render_reference(const RenderOptions& o, const Scene& scene,
                                         const CameraSpec& spec, const Job& job) {
  std::optional<RayCaster> caster;
  std::optional<PathTracer> tracer;
  job.step([&] {
    caster.emplace(scene);
    tracer.emplace(scene);
  });
  ProgressBar bar("render");
  Image image = render_path_traced(scene, *caster, Camera(spec), *tracer, o.samples,
                                   pixel_progress(bar, spec), job)
                    .radiosity;
  bar.finish();
  if (!job.is_root()) return std::nullopt;
  return Rendered{std::move(image), std::nullopt, {}};
}

/// The plain renders, the root's alone: the solution's patches, the albedo, the facing ratio.
Rendered render_plain(const RenderOptions& o, const MethodTraits& m, const Inputs& inputs,
                      const CameraSpec& spec) {
  const Camera camera(spec);
  if (m.kind == MethodKind::patches)
    return {render_patches(inputs.scene, *inputs.solution, camera, !o.no_ambient), {}, {}};
  const RayCaster caster(inputs.scene);
  return {
      m.kind == MethodKind::facing ? render_facing(caster, camera) : render_albedo(caster, camera),
      {},
      {}};
}

/// The files a render writes: the image, its preview, and for the local pass the stats JSON and
/// the per-pixel channels beside it (empty when not written).
struct RenderPaths {
  std::filesystem::path image, preview, stats, pixels;
};

RenderPaths render_paths(const RenderOptions& o, const MethodTraits& m) {
  RenderPaths out;
  out.image = o.output;
  if (!o.no_preview) {
    out.preview = o.preview.empty() ? std::filesystem::path(o.output).replace_extension(".png")
                                    : std::filesystem::path(o.preview);
  }
  if (m.kind == MethodKind::local_pass) {
    out.stats = o.stats.empty() ? std::filesystem::path(o.output).replace_extension(".stats.json")
                                : std::filesystem::path(o.stats);
    out.pixels =
        std::filesystem::path(out.stats).replace_extension().replace_extension(".pixels.exr");
  }
  return out;
}

/// Writes the image, its preview and, for the local pass, the stats JSON and the per-pixel
/// channels, as a whole (CommitGroup: every file is written before any is replaced). Returns
/// the paths written, for the summary line.
std::string write_render_outputs(const RenderPaths& paths, Rendered& r,
                                 std::optional<double> exposure) {
  CommitGroup group;
  write_exr(paths.image, r.image);
  std::string written = paths.image.string();
  if (!paths.preview.empty()) {
    const double stops = exposure ? *exposure : auto_exposure(r.image);
    write_png_preview(paths.preview, r.image, stops);
    std::ostringstream text;
    text.precision(3);
    text << ", " << paths.preview.string() << " (exposure " << std::showpos << stops
         << (exposure ? ")" : ", from the image)");
    written += text.str();
  }
  if (r.stats) {
    write_exr_channels(paths.pixels, r.pixel_stats);
    r.stats->pixels_file = paths.pixels.filename().string();
    write_render_stats(paths.stats, *r.stats);
    written += ", " + paths.stats.string() + ", " + paths.pixels.string();
  }
  group.commit();
  return written;
}

/// The summary lines on stderr: what ran, the size, the time, the files; for the exact methods
/// the faces gathered and the largest relative bound.
void report_render(const RenderOptions& o, const MethodTraits& m, const CameraSpec& spec,
                   const Rendered& r, const std::string& written, double seconds) {
  std::cerr << "render: " << o.method
            << (m.exact ? " at tolerance " + std::to_string(o.tolerance)
                : m.kind == MethodKind::local_pass
                    ? " with " + std::to_string(o.samples) + " samples per pixel"
                : m.kind == MethodKind::path_tracer
                    ? " with " + std::to_string(o.samples) + " paths per pixel"
                    : std::string())
            << " " << spec.width << "x" << spec.height << " in " << seconds << " s; wrote "
            << written << "\n";
  if (m.exact) {
    std::cerr << "render: faces gathered exactly per pixel: mean " << r.stats->emitting_mean
              << " of " << r.stats->faces << "; largest relative bound "
              << r.stats->relative_bound_max << "\n";
    if (r.stats->pixels_interpolated > 0) {
      std::cerr << "render: " << r.stats->pixels_interpolated << " of " << r.stats->pixels_gathered
                << " pixels interpolated in cells of " << r.stats->tile
                << " (certified: localpass/tile_gather.h)\n";
    }
  }
}

void run_render(const RenderOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const ThreadLimit limit(o.threads);
  const MethodTraits& m = method_traits(o.method);
  check_solution_use(m, !o.solution.empty(), MethodCommand::render);
  // Over an MPI job the local pass and the path tracer split their tiles over the processes;
  // the plain renders are the root's alone.
  if (!m.distributable && !Job::world().is_root()) return;
  const Job& job = m.distributable ? Job::world() : Job::alone();
  const bool needs_solution = m.solution == SolutionUse::required;
  const Inputs inputs = load_inputs(job, o.scene, needs_solution ? o.solution : std::string());
  CameraSpec spec;
  const RenderPaths paths = render_paths(o, m);
  job.step([&] {
    spec = camera_for(inputs.scene, o.scene, "render", o.width, o.height);
    // Refused now, not after the work: an output over an input, or two outputs in one file.
    if (job.is_root()) {
      check_outputs({{"the image (-o)", paths.image},
                     {"the preview (--preview)", paths.preview},
                     {"the stats JSON (--stats)", paths.stats},
                     {"the per-pixel statistics", paths.pixels}});
    }
  });

  std::optional<Rendered> rendered;
  if (m.kind == MethodKind::local_pass) {
    rendered = render_from_solution(o, m, inputs, spec, job, start);
  } else if (m.kind == MethodKind::path_tracer) {
    rendered = render_reference(o, inputs.scene, spec, job);
  } else {
    rendered = render_plain(o, m, inputs, spec);
  }
  if (!rendered) return;  // a process other than the root of an MPI job
  const std::string written = write_render_outputs(paths, *rendered, o.exposure);
  report_render(o, m, spec, *rendered, written, seconds_since(start));
}

}  // namespace

void add_render_command(CLI::App& app, Run& run) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* sub = app.add_subcommand(
      "render", "Render an image from the scene camera (OpenEXR + PNG preview).");
  sub->footer(
      "Writes IMAGE.exr (linear float RGB: the radiosity B at the visible point, W/m^2 when "
      "lengths are\n"
      "metres; the radiance of a diffuse surface is B/pi) and a PNG preview beside it (linear x\n"
      "2^exposure, clamped, sRGB; the exposure is chosen from the image unless given). "
      "hemisphere,\n"
      "vertex and montecarlo also write IMAGE.stats.json (counts, bound statistics, time) and\n"
      "IMAGE.pixels.exr (per-pixel channels projected, emitting, surface, and for the exact "
      "methods\n"
      "bound and relative_bound, and refracted where light comes through refracting materials: the "
      "part\n"
      "of B from the heuristic of paper 000 section 4, which the bound does not cover; export "
      "--stats\n"
      "turns it into a VTK image), and show a progress bar on a terminal. All methods but albedo "
      "and\n"
      "facing need --solution, and refuse one solved for a different scene. Parallel over 16x16 "
      "pixel\n"
      "tiles; the image does not depend on the thread count. Under mpirun the tiles are spread "
      "over the\n"
      "processes, with the same bytes out (docs/cluster.md). File contents: docs/formats.md.");
  sub->add_option("scene", o->scene, kSceneHelp)->required();
  sub->add_option(
         "-m,--method", o->method,
         "hemisphere | vertex: the error-bounded local pass (004 Fig. 6) with the exact hemisphere "
         "gather or vertex tracing, B = E + rho H at the visible point (needs --solution); "
         "montecarlo: the same B with H from --samples cosine-weighted rays into the solution (the "
         "baseline; needs --solution); "
         "patches: the solution's element radiosities, Gouraud-interpolated (needs --solution); "
         "albedo: primary rays only (reflectance; emitters show their emission); "
         "facing: albedo x |cos| to the eye, to see the geometry; "
         "pathtrace: the reference, B with H from --samples paths of the scene itself, every "
         "bounce sampled (no solution)")
      ->check(CLI::IsMember(method_names_for(MethodCommand::render)))
      ->capture_default_str();
  add_refraction_options(sub, &o->settings);
  add_glossy_options(sub, &o->settings);
  add_tolerance_option(
      sub, &o->tolerance,
      "hemisphere/vertex: stop gathering a pixel once its certified error bound is at most this "
      "fraction of its value (0: exact)");
  add_samples_option(sub, &o->samples, "pixel");
  sub->add_option("--tile", o->settings.tile,
                  "hemisphere/vertex: certified interpolation over cells of this many pixels a "
                  "side: a cell's corners are gathered, the light that reaches all of it "
                  "unhidden is interpolated with a bound on the error, the rest gathered per "
                  "pixel, where that is less work than gathering the pixel on its own; each "
                  "pixel keeps its certified bound (0 or 1: every pixel on its own; never at "
                  "tolerance 0)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  sub->add_option("--stats", o->stats,
                  "hemisphere/vertex/montecarlo: stats JSON path (default: OUTPUT with "
                  ".stats.json; -: stdout)");
  add_solution_option(sub, &o->solution);
  sub->add_flag("--no-ambient", o->no_ambient, "patches: leave out the display-only ambient term");
  sub->add_flag("--no-mirror-culling", o->no_mirror_culling,
                "Exact methods: gather every mirror chain at every point facing its first mirror "
                "(no culling beams, paper 000 §5; the same image, slower: for measuring them)");
  sub->add_option("-o,--output", o->output, "Output image (.exr, linear float RGB)")->required();
  sub->add_option("--preview", o->preview, "PNG preview path (default: OUTPUT with .png)");
  sub->add_flag("--no-preview", o->no_preview, "Do not write the PNG preview");
  add_image_size_options(sub, &o->width, &o->height);
  sub->add_option("--exposure", o->exposure,
                  "Preview exposure in stops (PNG = linear * 2^exposure; default: the one that "
                  "makes the image's 95th-percentile pixel white)")
      ->check(kFinite);
  add_threads_option(sub, &o->threads);
  sub->callback([o, &run] { run = [o] { run_render(*o); }; });
}

}  // namespace rad::cli
