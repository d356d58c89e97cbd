#include "experiments/error_map.h"

#include <cmath>
#include <limits>
#include <string>

#include "formats/image_io.h"
#include "scene/error.h"

namespace rad {

ErrorMap relative_error_map(const Image& image, const Image& reference, double floor) {
  if (image.width != reference.width || image.height != reference.height) {
    throw Error("images differ in size: " + std::to_string(image.width) + "x" +
                std::to_string(image.height) + " against the reference's " +
                std::to_string(reference.width) + "x" + std::to_string(reference.height));
  }
  ErrorMap map;
  map.width = image.width;
  map.height = image.height;
  map.relative.assign(image.pixels.size(), std::numeric_limits<double>::quiet_NaN());
  double threshold = 0;
  if (floor > 0) {
    double positive_sum = 0;
    size_t positive = 0;
    for (const Rgb& r : reference.pixels) {
      const double ref = r.maxCoeff();
      if (ref > 0 && std::isfinite(ref)) positive_sum += ref, ++positive;
    }
    threshold = positive > 0 ? floor * positive_sum / static_cast<double>(positive) : 0;
  }
  double sum = 0, sum_squares = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const double ref = reference.pixels[i].maxCoeff();
    if (!(ref > threshold) || !(ref > 0) || !std::isfinite(ref)) {
      ++map.stats.skipped;
      continue;
    }
    double e = (image.pixels[i] - reference.pixels[i]).cwiseAbs().maxCoeff() / ref;
    if (std::isnan(e)) e = std::numeric_limits<double>::infinity();
    map.relative[i] = e;
    map.stats.max = std::max(map.stats.max, e);
    sum += e;
    sum_squares += e * e;
    ++map.stats.pixels;
  }
  if (map.stats.pixels > 0) {
    map.stats.mean = sum / map.stats.pixels;
    map.stats.rms = std::sqrt(sum_squares / map.stats.pixels);
  }
  return map;
}

void write_error_map_exr(const std::filesystem::path& exr, const ErrorMap& map) {
  Image image(map.width, map.height);
  for (size_t i = 0; i < map.relative.size(); ++i) {
    const double e = std::isnan(map.relative[i]) ? 0 : map.relative[i];
    image.pixels[i] = Rgb::Constant(e);
  }
  write_exr(exr, image);
}

}  // namespace rad
