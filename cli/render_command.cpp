// `radiosity render SCENE [--solution S.vtp] --method hemisphere|vertex|patches|albedo|facing
// [--tolerance T] -o IMAGE.exr`: per-pixel images from the scene camera; the exact methods run
// the error-bounded local pass and write a stats JSON next to the image.
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli/commands.h"
#include "cli/common.h"
#include "cli/inputs.h"
#include "distributed/job.h"
#include "formats/atomic_file.h"
#include "formats/image_io.h"
#include "formats/solution_io.h"
#include "localpass/method.h"
#include "radiosity/solution_faces.h"
#include "reference/path_tracer.h"
#include "render/albedo_render.h"
#include "render/irradiance_render.h"
#include "render/patch_render.h"
#include "scene/error.h"
#include "scene/ray_caster.h"

namespace rad::cli {
namespace {

/// The local pass's methods (localpass/method.h) and the plain renders.
std::vector<std::string> render_method_names() {
  std::vector<std::string> names = method_names();
  for (const char* plain : {"patches", "albedo", "facing", "pathtrace"}) names.emplace_back(plain);
  return names;
}

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
  int width = 0, height = 0;  ///< 0: the scene camera's
  double exposure = 0;
  int threads = 0;  ///< 0: all cores
};

/// Per-pixel statistics of a local-pass render, as written to the stats JSON.
nlohmann::json local_pass_stats(const RenderOptions& o, const IrradianceImage& image,
                                int face_count, int leaves, double seconds) {
  IrradianceSummary summary = summarize(image);
  if (image.samples_per_pixel > 0) {
    // Monte Carlo: the file has always reported the rays per pixel in these fields.
    summary.gathered_exactly_mean = summary.projected_mean = image.samples_per_pixel;
    summary.gathered_exactly_max = summary.projected_max = image.samples_per_pixel;
  }
  const double faces = face_count;
  nlohmann::json out;
  out["method"] = o.method;
  if (image.samples_per_pixel > 0) {
    out["samples"] = o.samples;
  } else {
    out["tolerance"] = o.tolerance;
  }
  out["width"] = image.radiosity.width;
  out["height"] = image.radiosity.height;
  out["seconds"] = seconds;
  out["threads"] = tbb::this_task_arena::max_concurrency();  // a process's
  out["processes"] = Job::world().size();
  out["faces"] = face_count;
  out["octree_leaves"] = leaves;
  out["pixels_gathered"] = summary.pixels;
  out["emitting_per_pixel"] = {{"mean", summary.gathered_exactly_mean},
                               {"max", summary.gathered_exactly_max}};
  out["emitting_fraction_mean"] = summary.gathered_exactly_mean / faces;
  out["projected_per_pixel"] = {{"mean", summary.projected_mean}, {"max", summary.projected_max}};
  out["projected_fraction_mean"] = summary.projected_mean / faces;
  out["clusters_per_pixel"] = {{"mean", summary.clusters_mean}};
  out["bound"] = {{"relative_mean", summary.relative_bound_mean},
                  {"relative_max", summary.relative_bound_max},
                  {"max", summary.bound_max}};
  // The heuristic parts (000 §4's refraction, 003's glossy beams), apart from the bound (which
  // covers the rest).
  double total_sum = 0;
  for (const Rgb& b : image.radiosity.pixels) total_sum += b.sum();
  for (const auto& [name, part] : image.heuristic_parts()) {
    size_t pixels = 0;
    double sum = 0;
    for (const Rgb& r : part->pixels) pixels += r.sum() > 0, sum += r.sum();
    if (pixels == 0) continue;
    out[name] = {{"pixels", pixels},
                 {"share_of_light", total_sum > 0 ? sum / total_sum : 0.0},
                 {"certified", false}};
  }
  return out;
}

/// Per-pixel statistics for `export --stats`: faces projected and gathered (rays, for Monte
/// Carlo), for the exact methods the certified bound on B (largest channel) and the bound
/// relative to B, and 1 where a front-facing surface was gathered.
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
  bound.resize(n);
  relative.resize(n);
  for (size_t i = 0; i < n; ++i) {
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

void run_render(const RenderOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const ThreadLimit limit(o.threads);
  // A method of the local pass (localpass/method.h), or one of the plain renders.
  const std::optional<Method> method = parse_method(o.method);
  const bool local = method.has_value();
  const bool needs_solution = local || o.method == "patches";
  if (needs_solution && o.solution.empty()) {
    throw InputError("--method " + o.method +
                     " needs --solution (a .vtp written by `radiosity solve`)");
  }
  if (o.method == "pathtrace" && !o.solution.empty())
    throw InputError("--method pathtrace traces the scene itself: it takes no --solution");
  // Over an MPI job the local pass and the path tracer split their tiles over the processes;
  // the plain renders are the root's alone.
  const bool split = local || o.method == "pathtrace";
  if (!split && !Job::world().is_root()) return;
  const Job& job = split ? Job::world() : Job::alone();
  const Inputs inputs = load_inputs(job, o.scene, needs_solution ? o.solution : std::string());
  const Scene& scene = inputs.scene;
  CameraSpec spec;
  job.step([&] { spec = camera_for(scene, o.scene, "render", o.width, o.height); });
  const Camera camera(spec);

  Image image;
  nlohmann::json stats;
  ChannelImage pixel_stats;  // local methods: per-pixel statistics, beside the stats JSON
  if (needs_solution) {
    const Solution& solution = *inputs.solution;
    if (local) {
      std::vector<EmittingFace> faces;
      std::optional<RayCaster> caster;
      std::optional<LocalPass> pass;
      std::optional<MonteCarloGatherer> monte_carlo;
      job.step([&] {
        faces = faces_from_solution(scene, solution);
        caster.emplace(scene);
        if (!is_exact(*method)) {
          monte_carlo.emplace(scene, faces);
        } else {
          LocalPassSettings settings = o.settings;
          settings.mirror_culling = !o.no_mirror_culling;
          pass.emplace(scene, faces, *method, settings);
        }
      });
      ProgressBar bar("render");
      const double total = static_cast<double>(spec.width) * spec.height;
      const auto progress = [&](size_t done) {
        bar.update(done / total, std::to_string(done) + " pixels");
      };
      const IrradianceImage result =
          pass ? render_local_pass(scene, *caster, camera, *pass, o.tolerance, progress, job)
               : render_monte_carlo(scene, *caster, camera, *monte_carlo, o.samples, progress, job);
      bar.finish();
      if (!job.is_root()) return;  // its image holds only the tiles it rendered
      image = result.radiosity;
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      stats =
          local_pass_stats(o, result, static_cast<int>(faces.size()),
                           pass ? static_cast<int>(pass->octree().leaves().size()) : 0, seconds);
      pixel_stats = pixel_channels(result, is_exact(*method));
    } else {
      image = render_patches(scene, solution, camera, !o.no_ambient);
    }
  } else if (o.method == "pathtrace") {
    std::optional<RayCaster> caster;
    std::optional<PathTracer> tracer;
    job.step([&] {
      caster.emplace(scene);
      tracer.emplace(scene);
    });
    ProgressBar bar("render");
    const double total = static_cast<double>(spec.width) * spec.height;
    image =
        render_path_traced(
            scene, *caster, camera, *tracer, o.samples,
            [&](size_t done) { bar.update(done / total, std::to_string(done) + " pixels"); }, job)
            .radiosity;
    bar.finish();
    if (!job.is_root()) return;
  } else {
    const RayCaster caster(scene);
    image = o.method == "facing" ? render_facing(caster, camera) : render_albedo(caster, camera);
  }

  write_exr(o.output, image);
  std::string written = o.output;
  if (!o.no_preview) {
    std::filesystem::path png = o.preview.empty()
                                    ? std::filesystem::path(o.output).replace_extension(".png")
                                    : std::filesystem::path(o.preview);
    write_png_preview(png, image, o.exposure);
    written += ", " + png.string();
  }
  if (local) {
    const std::filesystem::path path =
        o.stats.empty() ? std::filesystem::path(o.output).replace_extension(".stats.json")
                        : std::filesystem::path(o.stats);
    const std::filesystem::path pixels =
        std::filesystem::path(path).replace_extension().replace_extension(".pixels.exr");
    write_exr_channels(pixels, pixel_stats);
    stats["pixels_file"] = pixels.filename().string();
    write_text_file(path, [&](std::ostream& file) { file << stats.dump(2) << "\n"; });
    written += ", " + path.string() + ", " + pixels.string();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const bool exact = local && is_exact(*method);
  std::cerr << "render: " << o.method
            << (exact   ? " at tolerance " + std::to_string(o.tolerance)
                : local ? " with " + std::to_string(o.samples) + " samples per pixel"
                : o.method == "pathtrace"
                    ? " with " + std::to_string(o.samples) + " paths per pixel"
                    : std::string())
            << " " << spec.width << "x" << spec.height << " in " << seconds << " s; wrote "
            << written << "\n";
  if (exact) {
    std::cerr << "render: faces gathered exactly per pixel: mean "
              << stats["emitting_per_pixel"]["mean"].get<double>() << " of "
              << stats["faces"].get<int>() << "; largest relative bound "
              << stats["bound"]["relative_max"].get<double>() << "\n";
  }
}

}  // namespace

void add_render_command(CLI::App& app, Run& run) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* sub = app.add_subcommand(
      "render", "Render an image from the scene camera (OpenEXR + PNG preview).");
  sub->footer(
      "Writes IMAGE.exr (linear float RGB) and a PNG preview beside it (linear x 2^exposure, "
      "clamped,\n"
      "sRGB). hemisphere, vertex and montecarlo also write IMAGE.stats.json (counts, bound "
      "statistics,\n"
      "time) and IMAGE.pixels.exr (per-pixel channels projected, emitting, surface, and for the "
      "exact\n"
      "methods bound and relative_bound, and refracted where light comes through refracting "
      "materials:\n"
      "the part of B from the heuristic of paper 000 section 4, which the bound does not cover; "
      "export\n"
      "--stats turns it into a VTK image), and show a progress\n"
      "bar on a terminal. All methods but albedo and facing need --solution, and refuse one solved "
      "for\n"
      "a different scene. Parallel over 16x16 pixel tiles; the image does not depend on the "
      "thread\n"
      "count. Under mpirun the tiles are spread over the processes, with the same bytes out\n"
      "(docs/cluster.md). File contents: docs/formats.md.");
  sub->add_option("scene", o->scene, "Scene file (JSON) with a camera block")->required();
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
      ->check(CLI::IsMember(render_method_names()))
      ->capture_default_str();
  add_refraction_options(sub, &o->settings);
  add_glossy_options(sub, &o->settings);
  add_tolerance_option(
      sub, &o->tolerance,
      "hemisphere/vertex: stop gathering a pixel once its certified error bound is at most this "
      "fraction of its value (0: exact)");
  add_samples_option(sub, &o->samples, "pixel");
  sub->add_option(
      "--stats", o->stats,
      "hemisphere/vertex/montecarlo: stats JSON path (default: OUTPUT with .stats.json)");
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
                  "Preview exposure in stops (PNG = linear * 2^exposure)")
      ->capture_default_str();
  add_threads_option(sub, &o->threads);
  sub->callback([o, &run] { run = [o] { run_render(*o); }; });
}

}  // namespace rad::cli
