// `radiosity export SCENE --solution S.vtp -o DIR [--stats IMAGE.stats.json]`: files for
// ParaView (the patch mesh, the octree, a render's per-pixel statistics) and a picture of the
// patch mesh from the scene camera.
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/common.h"
#include "formats/image_io.h"
#include "formats/render_stats.h"
#include "formats/solution_io.h"
#include "localpass/local_pass.h"
#include "octree/octree.h"
#include "radiosity/solution_faces.h"
#include "scene/polygon_faces.h"
#include "viz/vtk_export.h"

namespace rad::cli {
namespace {

struct ExportOptions {
  std::string scene, solution, output, stats;
  int width = 0, height = 0;
  std::optional<double> exposure;  ///< none: chosen from the radiosities
  bool no_png = false;
};

void run_export(const ExportOptions& o) {
  const Scene scene = load_scene_reporting(o.scene);
  const Solution solution = load_solution_for(scene, o.scene, o.solution);
  const std::filesystem::path folder(o.output);
  std::vector<std::string> written;

  // Read the statistics and check the camera first: bad input fails before anything is written.
  ChannelImage pixels;
  if (!o.stats.empty()) pixels = read_exr_channels(pixels_file_of(o.stats));
  std::optional<CameraSpec> camera;
  if (!o.no_png)
    camera =
        camera_for(scene, o.scene, "export (for patch_mesh.png; or --no-png)", o.width, o.height);

  write_solution(folder / "patch_mesh.vtp", solution, scene);
  written.push_back("patch_mesh.vtp");

  const Octree octree(octree_items(faces_from_solution(scene, solution)));
  write_octree_vtu(folder / "octree.vtu", octree);
  written.push_back("octree.vtu (" + std::to_string(octree.leaves().size()) + " leaves)");

  if (!o.stats.empty()) {
    write_pixel_image_vti(folder / "pixel_stats.vti", pixels.width, pixels.height, pixels.channels);
    written.push_back("pixel_stats.vti");
  }
  if (!o.no_png) {
    write_patch_mesh_png(folder / "patch_mesh.png", solution, scene, *camera, o.exposure);
    written.push_back("patch_mesh.png");
  }
  std::cerr << "export: wrote to " << folder.string() << "/:";
  for (const std::string& w : written) std::cerr << " " << w << (&w == &written.back() ? "" : ",");
  std::cerr << "\n";
}

}  // namespace

void add_export_command(CLI::App& app, Run& run) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* sub = app.add_subcommand("export",
                                     "VTK XML files for ParaView: the patch mesh (patch_mesh.vtp: "
                                     "radiosity, emission, reflectance, refinement "
                                     "level), the octree (octree.vtu: hexahedra with bmax, "
                                     "patch_count, energy), with --stats a render's "
                                     "per-pixel statistics (pixel_stats.vti); and patch_mesh.png, "
                                     "the mesh coloured by radiosity from the scene "
                                     "camera.");
  sub->footer(
      "Writes to the folder: patch_mesh.vtp (the leaf elements with cell data radiosity, "
      "emission,\n"
      "reflectance, level, parent_polygon, patch, area: the solution file's format), octree.vtu "
      "(every\n"
      "non-empty voxel of the local pass's octree as a hexahedron with cell data bmax (004 eq. "
      "5),\n"
      "bmax_max, patch_count, energy, level, leaf: threshold leaf = 1 to see the leaves), with "
      "--stats\n"
      "pixel_stats.vti (a render's per-pixel statistics as an image, right side up), and\n"
      "patch_mesh.png (the elements flat-coloured by radiosity with their edges, from the scene\n"
      "camera; needs an X display, a private Xvfb is started without $DISPLAY; --no-png skips "
      "it).");
  sub->add_option("scene", o->scene, kSceneHelp)->required();
  add_solution_option(sub, &o->solution)->required();
  sub->add_option("-o,--output", o->output, "Output folder (created if missing)")->required();
  sub->add_option(
      "--stats", o->stats,
      "Stats JSON written by `radiosity render` (IMAGE.stats.json): export its per-pixel faces "
      "projected and bound as pixel_stats.vti");
  add_image_size_options(sub, &o->width, &o->height, "patch_mesh.png");
  sub->add_option("--exposure", o->exposure,
                  "patch_mesh.png exposure in stops (linear * 2^exposure; default: the one "
                  "that makes the 95th-percentile element white)")
      ->check(kFinite);
  sub->add_flag("--no-png", o->no_png, "Do not draw patch_mesh.png (no X display or Xvfb needed)");
  sub->callback([o, &run] { run = [o] { run_export(*o); }; });
}

}  // namespace rad::cli
