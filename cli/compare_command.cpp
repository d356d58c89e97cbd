// `radiosity compare IMAGE.exr REFERENCE.exr [-o MAP.exr]`: relative error statistics of an
// image against a reference, and the error map (OpenEXR + PNG heat map with a colour bar).
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/common.h"
#include "experiments/error_map.h"
#include "formats/atomic_file.h"
#include "formats/image_io.h"
#include "scene/error.h"
#include "viz/error_heat_map.h"

namespace rad::cli {
namespace {

struct CompareOptions {
  std::string image, reference, map, png;
  bool no_png = false;
  double max = 0;
  double floor = 0;
};

void run_compare(const CompareOptions& o) {
  const Image image = read_exr(o.image);
  const Image reference = read_exr(o.reference);
  std::filesystem::path png;
  if (!o.map.empty() && !o.no_png)
    png = o.png.empty() ? std::filesystem::path(o.map).replace_extension(".png")
                        : std::filesystem::path(o.png);
  // -o map.png would write the EXR and then the heat map into one file; refused before the work.
  check_outputs({{"the error map (-o)", o.map}, {"the heat map (--png)", png}});
  if (image.width != reference.width || image.height != reference.height) {
    throw InputError(o.image + ": " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + " pixels, but the reference " + o.reference +
                     " has " + std::to_string(reference.width) + "x" +
                     std::to_string(reference.height));
  }
  const ErrorMap map = relative_error_map(image, reference, o.floor);
  if (map.stats.pixels == 0) {
    throw InputError(o.reference + ": no pixel to compare: the reference is 0 everywhere" +
                     (o.floor > 0 ? std::string(" or below the floor") : std::string()));
  }
  std::cout << "image: " << o.image << "\nreference: " << o.reference
            << "\npixels compared: " << map.stats.pixels << " (skipped " << map.stats.skipped
            << (o.floor > 0 ? " where the reference is below the floor)\n"
                            : " where the reference is 0)\n")
            << "max relative error: " << map.stats.max
            << "\nmean relative error: " << map.stats.mean
            << "\nRMS relative error: " << map.stats.rms << "\n";
  if (o.map.empty()) return;
  CommitGroup group;  // the map and its heat map replace the old ones together
  write_error_map_exr(o.map, map);
  if (!png.empty()) {
    write_error_heat_map(png, map,
                         "relative error of " + std::filesystem::path(o.image).filename().string() +
                             " against " + std::filesystem::path(o.reference).filename().string(),
                         o.max);
  }
  group.commit();
  std::cerr << "compare: wrote " << o.map << (png.empty() ? "" : ", " + png.string()) << "\n";
}

}  // namespace

void add_compare_command(CLI::App& app, Run& run) {
  auto o = std::make_shared<CompareOptions>();
  CLI::App* sub = app.add_subcommand("compare",
                                     "Relative error of an image against a reference, per pixel |I "
                                     "- R| / R on the brightest channel: prints "
                                     "max, mean and RMS over the pixels where the reference is "
                                     "positive; with -o writes the error map.");
  sub->footer(
      "Per pixel e = max_c |I_c - R_c| / max_c R_c over the pixels where the reference is "
      "positive;\n"
      "prints the pixels compared and skipped and the max, mean and RMS of e on stdout. With -o: "
      "the\n"
      "error map as OpenEXR (e in R, G and B; 0 where not compared) and a PNG heat map beside it "
      "with a\n"
      "colour bar (0 to --max, default the largest error; grey where not compared). Images of "
      "different\n"
      "sizes are an error (exit 1).");
  sub->add_option("image", o->image, "Image to judge (OpenEXR)")->required();
  sub->add_option("reference", o->reference, "Reference image (OpenEXR), e.g. a tolerance-0 render")
      ->required();
  sub->add_option("-o,--output", o->map,
                  "Error map (.exr: the relative error in R, G, B; 0 where not compared)");
  sub->add_option("--png", o->png, "Heat map PNG with a colour bar (default: OUTPUT with .png)");
  sub->add_flag("--no-png", o->no_png, "Do not write the heat map");
  sub->add_option("--max", o->max,
                  "Error at the top of the colour bar (default: the largest error)")
      ->check(CLI::PositiveNumber)
      ->check(kFinite);
  sub->add_option("--floor", o->floor,
                  "Compare only pixels whose reference exceeds this fraction of its mean (a "
                  "sampled reference is noise alone in the dark); default 0: every lit pixel")
      ->check(CLI::Range(0.0, 1.0))
      ->check(kFinite)
      ->capture_default_str();
  sub->callback([o, &run] { run = [o] { run_compare(*o); }; });
}

}  // namespace rad::cli
