#include "formats/image_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <unistd.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>

#include <algorithm>
#include <cmath>
#include <exception>

#include "formats/atomic_file.h"
#include "formats/exr_guard.h"
#include "scene/error.h"
#include "scene/input_files.h"
#include "scene/limits.h"

namespace rad {

void write_exr_channels(const std::filesystem::path& file, const ChannelImage& image) {
  const size_t n = static_cast<size_t>(image.width) * image.height;
  AtomicFile out(file);
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer frame;
    for (const auto& [name, values] : image.channels) {
      if (values.size() != n) throw Error("channel " + name + " has the wrong size");
      header.channels().insert(name, Imf::Channel(Imf::FLOAT));
      // OpenEXR only reads from the frame buffer; the cast drops const for its interface.
      frame.insert(
          name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(values.data())),
                           sizeof(float), sizeof(float) * image.width));
    }
    Imf::OutputFile exr(out.temp_path().c_str(), header);
    exr.setFrameBuffer(frame);
    exr.writePixels(image.height);
  } catch (const std::exception& e) {
    throw Error(file.string() + ": cannot write OpenEXR: " + e.what());
  }
  out.commit();
}

ChannelImage read_exr_channels(const std::filesystem::path& file) {
  check_input_file(file, "image file");
  try {
    // OpenEXR's own limits, which it checks as it reads the header (Header::sanityCheck), before
    // it sizes its tables of chunk offsets from the data window.
    Imf::Header::setMaxImageSize(limits::kImageSide, limits::kImageSide);
    Imf::Header::setMaxTileSize(limits::kImageSide, limits::kImageSide);
    check_exr_claims(file);
    Imf::InputFile exr(file.c_str());
    check_exr_pixels(file, exr.header());
    const Imath::Box2i window = exr.header().dataWindow();
    ChannelImage image;
    image.width = window.max.x - window.min.x + 1;
    image.height = window.max.y - window.min.y + 1;
    const size_t n = static_cast<size_t>(image.width) * image.height;
    Imf::FrameBuffer frame;
    for (auto it = exr.header().channels().begin(); it != exr.header().channels().end(); ++it) {
      std::vector<float>& values = image.channels[it.name()];
      values.assign(n, 0.0f);
      // The slice base is shifted so that pixel (min.x, min.y) lands at index 0.
      char* base = reinterpret_cast<char*>(values.data()) -
                   (static_cast<ptrdiff_t>(window.min.x) +
                    static_cast<ptrdiff_t>(window.min.y) * image.width) *
                       static_cast<ptrdiff_t>(sizeof(float));
      frame.insert(it.name(), Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                         sizeof(float) * image.width, 1, 1, 0.0));
    }
    exr.setFrameBuffer(frame);
    exr.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(file.string() + ": cannot read OpenEXR: " + e.what());
  }
}

void write_exr(const std::filesystem::path& file, const Image& image) {
  ChannelImage channels{image.width, image.height, {}};
  const char* names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    std::vector<float>& plane = channels.channels[names[c]];
    plane.resize(image.pixels.size());
    for (size_t i = 0; i < plane.size(); ++i) plane[i] = static_cast<float>(image.pixels[i][c]);
  }
  write_exr_channels(file, channels);
}

Image read_exr(const std::filesystem::path& file) {
  const ChannelImage channels = read_exr_channels(file);
  Image image(channels.width, channels.height);
  const char* names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    const auto it = channels.channels.find(names[c]);
    if (it == channels.channels.end()) {
      // A Y-only image, or a render's per-pixel statistics: not an RGB image, whose missing
      // channels would read as 0 (and compare would find nothing to compare).
      std::string present;
      for (const auto& [name, values] : channels.channels)
        present += (present.empty() ? "" : ", ") + name;
      throw InputError(file.string() + ": no " + names[c] +
                       " channel: not an RGB image (its channels: " +
                       (present.empty() ? "none" : present) + ")");
    }
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i][c] = it->second[i];
  }
  // An image to compare or to measure against: a NaN or an infinity would compare as nothing
  // (every comparison with NaN is false). Renders never write one.
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    if (image.pixels[i].allFinite()) continue;
    throw InputError(file.string() + ": pixel (" + std::to_string(i % image.width) + ", " +
                     std::to_string(i / image.width) + ") is not a finite number");
  }
  return image;
}

double auto_exposure(std::vector<double> values) {
  std::erase_if(values, [](double v) { return !(v > 0 && std::isfinite(v)); });
  if (values.empty()) return 0;
  constexpr double kWhitePercentile = 0.95;
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(
                                       kWhitePercentile * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), at, values.end());
  return -std::log2(*at);
}

double auto_exposure(const Image& image) {
  std::vector<double> brightest;
  brightest.reserve(image.pixels.size());
  for (const Rgb& pixel : image.pixels) brightest.push_back(pixel.maxCoeff());
  return auto_exposure(std::move(brightest));
}

unsigned char to_srgb8(double linear, double exposure) {
  double v = std::clamp(linear * std::exp2(exposure), 0.0, 1.0);
  if (std::isnan(v)) v = 0;
  // sRGB transfer function (IEC 61966-2-1).
  const double encoded = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
  return static_cast<unsigned char>(std::lround(255.0 * encoded));
}

void write_png_preview(const std::filesystem::path& file, const Image& image, double exposure) {
  vtkNew<vtkImageData> data;
  data->SetDimensions(image.width, image.height, 1);
  data->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* bytes = static_cast<unsigned char*>(data->GetScalarPointer());
  for (int y = 0; y < image.height; ++y) {
    // VTK's image row 0 is the bottom row.
    unsigned char* row = bytes + 3 * static_cast<size_t>(image.height - 1 - y) * image.width;
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < 3; ++c) row[3 * x + c] = to_srgb8(image.at(x, y)[c], exposure);
    }
  }
  AtomicFile out(file);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(out.temp_path().c_str());
  writer->SetInputData(data);
  writer->Write();
  if (writer->GetErrorCode() != 0) throw Error(file.string() + ": cannot write PNG");
  out.commit();
}

}  // namespace rad
