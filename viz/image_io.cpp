#include "viz/image_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>

#include <algorithm>
#include <cmath>
#include <exception>

#include "scene/error.h"
#include "viz/atomic_file.h"

namespace rad {

void write_exr(const std::filesystem::path& file, const Image& image) {
  const size_t n = image.pixels.size();
  std::vector<float> planes[3];
  for (int c = 0; c < 3; ++c) {
    planes[c].resize(n);
    for (size_t i = 0; i < n; ++i) planes[c][i] = static_cast<float>(image.pixels[i][c]);
  }
  AtomicFile out(file);
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer frame;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(planes[c].data()),
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

Image read_exr(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file)) throw InputError(file.string() + ": no such image file");
  try {
    Imf::InputFile exr(file.c_str());
    const Imath::Box2i window = exr.header().dataWindow();
    const int width = window.max.x - window.min.x + 1;
    const int height = window.max.y - window.min.y + 1;
    const size_t n = static_cast<size_t>(width) * height;
    std::vector<float> planes[3];
    Imf::FrameBuffer frame;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
      planes[c].assign(n, 0.0f);
      // The slice base is shifted so that pixel (min.x, min.y) lands at index 0.
      char* base = reinterpret_cast<char*>(planes[c].data()) -
                   (static_cast<ptrdiff_t>(window.min.x) + static_cast<ptrdiff_t>(window.min.y) * width) *
                       static_cast<ptrdiff_t>(sizeof(float));
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * width, 1, 1, 0.0));
    }
    exr.setFrameBuffer(frame);
    exr.readPixels(window.min.y, window.max.y);
    Image image(width, height);
    for (size_t i = 0; i < n; ++i) image.pixels[i] = Rgb(planes[0][i], planes[1][i], planes[2][i]);
    return image;
  } catch (const std::exception& e) {
    throw InputError(file.string() + ": cannot read OpenEXR: " + e.what());
  }
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
