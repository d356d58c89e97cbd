// `radiosity render SCENE --method albedo|facing|patches [--solution S.vtp] -o IMAGE.exr`: per-pixel images from the scene camera.
#include <chrono>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/common.h"
#include "localpass/albedo_render.h"
#include "localpass/patch_render.h"
#include "scene/error.h"
#include "scene/ray_caster.h"
#include "viz/image_io.h"
#include "viz/solution_io.h"

namespace rad::cli {
namespace {

struct RenderOptions {
  std::string scene;
  std::string method = "albedo";
  std::string solution;  ///< .vtp from `solve`, for methods that need one
  bool no_ambient = false;
  std::string output;
  std::string preview;  ///< PNG path; default: the output with extension .png
  bool no_preview = false;
  int width = 0, height = 0;  ///< 0: the scene camera's
  double exposure = 0;
  int threads = 0;  ///< 0: all cores
};

void run_render(const RenderOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const ThreadLimit limit(o.threads);
  const bool needs_solution = o.method == "patches";
  if (needs_solution && o.solution.empty()) {
    throw InputError("--method " + o.method + " needs --solution (a .vtp written by `radiosity solve`)");
  }
  const Scene scene = load_scene_reporting(o.scene);
  if (!scene.camera) throw InputError(o.scene + ": no \"camera\" block; render needs one");
  CameraSpec spec = *scene.camera;
  if (o.width > 0) spec.width = o.width;
  if (o.height > 0) spec.height = o.height;
  const Camera camera(spec);

  Image image;
  if (needs_solution) {
    const Solution solution = read_solution(o.solution);
    if (solution.scene_fingerprint != scene.fingerprint()) {
      throw InputError(o.solution + ": solved for a different scene (" + solution.scene_path +
                       "); solve " + o.scene + " again");
    }
    image = render_patches(scene, solution, camera, !o.no_ambient);
  } else {
    const RayCaster caster(scene);
    image = o.method == "facing" ? render_facing(caster, camera) : render_albedo(caster, camera);
  }

  write_exr(o.output, image);
  std::string written = o.output;
  if (!o.no_preview) {
    std::filesystem::path png = o.preview.empty() ? std::filesystem::path(o.output).replace_extension(".png")
                                                  : std::filesystem::path(o.preview);
    write_png_preview(png, image, o.exposure);
    written += ", " + png.string();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cerr << "render: " << o.method << " " << spec.width << "x" << spec.height << " in "
            << seconds << " s; wrote " << written << "\n";
}

}  // namespace

void add_render_command(CLI::App& app, Run& run) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* sub = app.add_subcommand("render", "Render an image from the scene camera (OpenEXR + PNG preview).");
  sub->add_option("scene", o->scene, "Scene file (JSON) with a camera block")->required();
  sub->add_option("-m,--method", o->method,
                  "albedo: primary rays only (reflectance; emitters show their emission); "
                  "facing: albedo x |cos| to the eye, to see the geometry; "
                  "patches: the solution's element radiosities, Gouraud-interpolated (needs --solution)")
      ->check(CLI::IsMember({"albedo", "facing", "patches"}))
      ->capture_default_str();
  sub->add_option("-s,--solution", o->solution, "Solution file (.vtp) from `radiosity solve`");
  sub->add_flag("--no-ambient", o->no_ambient, "patches: leave out the display-only ambient term");
  sub->add_option("-o,--output", o->output, "Output image (.exr, linear float RGB)")->required();
  sub->add_option("--preview", o->preview, "PNG preview path (default: OUTPUT with .png)");
  sub->add_flag("--no-preview", o->no_preview, "Do not write the PNG preview");
  sub->add_option("--width", o->width, "Image width in pixels (default: the camera's)")->check(CLI::Range(1, 1 << 15));
  sub->add_option("--height", o->height, "Image height in pixels (default: the camera's)")->check(CLI::Range(1, 1 << 15));
  sub->add_option("--exposure", o->exposure, "Preview exposure in stops (PNG = linear * 2^exposure)")->capture_default_str();
  sub->add_option("-j,--threads", o->threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024));
  sub->callback([o, &run] { run = [o] { run_render(*o); }; });
}

}  // namespace rad::cli
