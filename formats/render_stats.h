#pragma once
/// The stats file a render of the local pass writes beside its image (IMAGE.stats.json; its
/// fields in docs/formats.md): written by `render`, read back by `export --stats`.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rad {

struct RenderStats {
  std::string method;
  std::optional<double> tolerance;  ///< The exact methods'.
  std::optional<int> samples;       ///< Monte Carlo's rays per pixel.
  int width = 0, height = 0;
  double seconds = 0;
  int threads = 0, processes = 1;  ///< A process's threads; the MPI job's processes.
  int faces = 0, octree_leaves = 0;
  size_t pixels_gathered = 0;
  int tile = 0;                    ///< The interpolation cells' side (0: off)
  size_t pixels_interpolated = 0;  ///< Of pixels_gathered, those a cell interpolated
  /// Faces gathered exactly and faces projected per pixel (Monte Carlo: its rays per pixel).
  double emitting_mean = 0, projected_mean = 0, clusters_mean = 0;
  int emitting_max = 0, projected_max = 0;
  /// The certified bound: relative to B (mean, max) and absolute (max; largest channel).
  double relative_bound_mean = 0, relative_bound_max = 0, bound_max = 0;
  /// A heuristic part of B (000 §4's refraction, 003's glossy beams), outside the bound.
  struct HeuristicPart {
    std::string name;
    size_t pixels = 0;  ///< pixels it lights
    double share_of_light = 0;
  };
  std::vector<HeuristicPart> heuristic_parts;
  std::string pixels_file;  ///< The per-pixel EXR beside it (its file name).
};

/// Writes `stats` as JSON (keys sorted, two-space indent) through a temporary file.
void write_render_stats(const std::filesystem::path& path, const RenderStats& stats);

/// The per-pixel file a stats JSON names ("pixels_file"), beside it. Throws InputError naming
/// the file when it cannot be read, is not JSON, or names no pixels file.
std::filesystem::path pixels_file_of(const std::filesystem::path& stats_path);

}  // namespace rad
