#pragma once
/// Per-pixel relative error of an image against a reference, its statistics, and the error map
/// as OpenEXR (the error in R, G and B). viz/error_heat_map.h draws it as a PNG heat map.
#include <filesystem>
#include <vector>

#include "formats/image.h"

namespace rad {

/// Statistics of the relative error over the compared pixels.
struct ErrorStats {
  double max = 0, mean = 0, rms = 0;
  size_t pixels = 0;   ///< Pixels compared: those where the reference is positive.
  size_t skipped = 0;  ///< Pixels not compared: the reference is 0 (background, back faces),
                       ///< or below the floor.
};

/// Per pixel, |image - reference| / reference on the brightest channel:
///   e = max_c |I_c - R_c| / max_c R_c,
/// the measure every table of this project uses. Pixels where max_c R_c <= 0 are not compared
/// (NaN in `relative`).
struct ErrorMap {
  int width = 0, height = 0;
  std::vector<double> relative;  ///< Row by row from the top.
  ErrorStats stats;
};

/// Throws Error when the sizes differ. A NaN in `image` where the reference is positive counts
/// as an infinite error (so it shows in `max`). With `floor` > 0, pixels whose max_c R_c is at
/// most floor times its mean over the positive pixels are not compared either: in the dark, a
/// sampled reference's noise is all there is, and the relative error means nothing.
ErrorMap relative_error_map(const Image& image, const Image& reference, double floor = 0);

/// Writes the relative error in all three channels (0 where not compared) as OpenEXR,
/// atomically (the heat map picture is viz/error_heat_map.h). Throws Error.
void write_error_map_exr(const std::filesystem::path& exr, const ErrorMap& map);

}  // namespace rad
