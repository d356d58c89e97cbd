#pragma once
/// Image files: OpenEXR for linear results (float RGB), PNG for tone-mapped previews.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "formats/image.h"

namespace rad {

/// Writes linear float RGB (channels R, G, B, ZIP compression) atomically. Throws Error.
void write_exr(const std::filesystem::path& file, const Image& image);

/// Reads the R, G, B channels of an OpenEXR file. Throws InputError naming the file when it is
/// missing, not an OpenEXR file, lacks one of R, G, B (a Y-only image, a render's per-pixel
/// statistics), or holds a pixel that is not a finite number.
Image read_exr(const std::filesystem::path& file);

/// Named float channels of one size (per-pixel statistics, say), rows from the top.
struct ChannelImage {
  int width = 0, height = 0;
  std::map<std::string, std::vector<float>> channels;
};

/// Writes every channel as FLOAT, ZIP compressed, atomically. Throws Error (also when a
/// channel's size is not width x height).
void write_exr_channels(const std::filesystem::path& file, const ChannelImage& image);

/// Reads every channel of an OpenEXR file as float. Throws InputError naming the file.
ChannelImage read_exr_channels(const std::filesystem::path& file);

/// The exposure (stops) a preview gets unless told one: the one that makes the 95th percentile
/// of the positive values white (linear 1), so that the brightest 5% (a lamp, a highlight)
/// clip and the rest keeps its shades; 0 when no value is positive. An image's radiosity is in
/// W/m^2 (DESIGN.md §3), whose scale is the scene's: a fixed exposure shows one scene washed out
/// and the next black.
double auto_exposure(std::vector<double> values);
/// auto_exposure of each pixel's brightest channel.
double auto_exposure(const Image& image);

/// 8-bit sRGB encoding of a linear value scaled by 2^exposure, clamped to [0, 1].
unsigned char to_srgb8(double linear, double exposure);

/// Writes a tone-mapped preview (linear * 2^exposure, clamped, sRGB-encoded) as an 8-bit RGB
/// PNG, atomically. Throws Error.
void write_png_preview(const std::filesystem::path& file, const Image& image, double exposure = 0);

}  // namespace rad
