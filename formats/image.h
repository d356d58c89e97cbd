#pragma once
/// A linear RGB image in double precision, the result type of every per-pixel pass.
#include <vector>

#include "geometry/vec.h"

namespace rad {

/// Row-major linear RGB, row 0 at the top (raster order of Camera).
struct Image {
  int width = 0;
  int height = 0;
  std::vector<Rgb> pixels;

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(static_cast<size_t>(w) * h, Rgb::Zero()) {}
  Rgb& at(int x, int y) { return pixels[static_cast<size_t>(y) * width + x]; }
  const Rgb& at(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

}  // namespace rad
