#include "formats/render_stats.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "formats/atomic_file.h"
#include "scene/error.h"
#include "scene/input_files.h"

namespace rad {

void write_render_stats(const std::filesystem::path& path, const RenderStats& s) {
  const double faces = s.faces;
  nlohmann::json out;
  out["method"] = s.method;
  if (s.samples) out["samples"] = *s.samples;
  if (s.tolerance) out["tolerance"] = *s.tolerance;
  out["width"] = s.width;
  out["height"] = s.height;
  out["seconds"] = s.seconds;
  out["threads"] = s.threads;
  out["processes"] = s.processes;
  out["faces"] = s.faces;
  out["octree_leaves"] = s.octree_leaves;
  out["pixels_gathered"] = s.pixels_gathered;
  out["interpolation"] = {{"tile", s.tile}, {"pixels", s.pixels_interpolated}};
  out["emitting_per_pixel"] = {{"mean", s.emitting_mean}, {"max", s.emitting_max}};
  out["emitting_fraction_mean"] = s.emitting_mean / faces;
  out["projected_per_pixel"] = {{"mean", s.projected_mean}, {"max", s.projected_max}};
  out["projected_fraction_mean"] = s.projected_mean / faces;
  out["clusters_per_pixel"] = {{"mean", s.clusters_mean}};
  out["bound"] = {{"relative_mean", s.relative_bound_mean},
                  {"relative_max", s.relative_bound_max},
                  {"max", s.bound_max}};
  for (const RenderStats::HeuristicPart& part : s.heuristic_parts) {
    out[part.name] = {
        {"pixels", part.pixels}, {"share_of_light", part.share_of_light}, {"certified", false}};
  }
  out["pixels_file"] = s.pixels_file;
  write_text_file(path, [&](std::ostream& file) { file << out.dump(2) << "\n"; });
}

std::filesystem::path pixels_file_of(const std::filesystem::path& stats_path) {
  const std::string name = stats_path.string();
  check_input_file(stats_path, "stats file");
  std::ifstream in(stats_path);
  if (!in) throw InputError(name + ": cannot open the stats file");
  nlohmann::json stats;
  try {
    in >> stats;
  } catch (const std::exception& e) {
    throw InputError(name + ": not a stats JSON from `radiosity render`: " + e.what());
  }
  if (!stats.is_object() || !stats.contains("pixels_file") || !stats["pixels_file"].is_string()) {
    throw InputError(name + ": no \"pixels_file\"; render the image again with this version");
  }
  return stats_path.parent_path() / stats["pixels_file"].get<std::string>();
}

}  // namespace rad
