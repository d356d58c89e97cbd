#include "formats/exr_guard.h"

#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "scene/error.h"
#include "scene/limits.h"

namespace rad {
namespace {

/// Scan lines in one chunk of a scan-line file, by compression (OpenEXR's numLinesInBuffer):
/// none, RLE, ZIPS: 1; ZIP, PXR24: 16; PIZ, B44, B44A, DWAA: 32; DWAB: 256. Unknown: 1, the
/// fewest, so the estimate of the chunk table never exceeds the truth.
long double lines_per_chunk(int compression) {
  switch (compression) {
    case 3:
    case 5:
      return 16;
    case 4:
    case 6:
    case 7:
    case 8:
      return 32;
    case 9:
      return 256;
    default:
      return 1;
  }
}

/// What one header says about the size of its image and its chunk table.
struct PartClaims {
  bool has_window = false;
  int32_t window[4] = {0, 0, 0, 0};  ///< min.x, min.y, max.x, max.y
  bool tiled = false;
  uint32_t tile[2] = {0, 0};
  int level_mode = 0;  ///< 0 one level, 1 mipmap, 2 ripmap
  int compression = 0;
};

uint32_t little_endian_u32(const unsigned char* b) {
  return static_cast<uint32_t>(b[0]) | static_cast<uint32_t>(b[1]) << 8 |
         static_cast<uint32_t>(b[2]) << 16 | static_cast<uint32_t>(b[3]) << 24;
}

/// Entries of the chunk-offset table of one part, as OpenEXR sizes it before reading it.
long double chunks_of(const PartClaims& part) {
  const long double width = 1.0L + part.window[2] - part.window[0];
  const long double height = 1.0L + part.window[3] - part.window[1];
  if (!part.tiled) return std::ceil(height / lines_per_chunk(part.compression));
  if (part.tile[0] == 0 || part.tile[1] == 0) return 0;  // OpenEXR refuses it
  const long double tiles = std::ceil(width / part.tile[0]) * std::ceil(height / part.tile[1]);
  // Mipmaps add at most a third, ripmaps at most three times (the levels halve each side);
  // a lower bound is what matters here, so the first level stands for them all.
  return tiles;
}

}  // namespace

void check_exr_claims(const std::filesystem::path& file) {
  std::error_code error;
  const std::uintmax_t bytes = std::filesystem::file_size(file, error);
  if (error) return;
  std::ifstream in(file, std::ios::binary);
  unsigned char magic[8];
  if (!in.read(reinterpret_cast<char*>(magic), 8) || little_endian_u32(magic) != 20000630) return;
  const uint32_t flags = little_endian_u32(magic + 4);
  const bool multipart = (flags & 0x1000) != 0;
  const bool single_tile = (flags & 0x200) != 0;

  const auto fail = [&](const std::string& detail) {
    throw InputError(file.string() + ": " + detail + " (not an OpenEXR image, or a damaged one)");
  };
  // A 0-terminated name of at most 255 characters; false if there is none (OpenEXR reports it).
  const auto read_name = [&](std::string& name) {
    name.clear();
    for (char c; in.get(c);) {
      if (c == '\0') return true;
      if (name.size() == 255) return false;
      name += c;
    }
    return false;
  };

  long double chunks = 0;
  for (int part = 0;; ++part) {
    PartClaims claims;
    claims.tiled = single_tile;
    int attributes = 0;
    for (std::string name, type; read_name(name) && !name.empty(); ++attributes) {
      unsigned char size_bytes[4];
      if (!read_name(type) || !in.read(reinterpret_cast<char*>(size_bytes), 4)) return;
      const auto size = static_cast<int32_t>(little_endian_u32(size_bytes));
      const auto at = static_cast<std::uintmax_t>(in.tellg());
      if (size < 0 || at + static_cast<std::uintmax_t>(size) > bytes) {
        fail("header attribute \"" + name + "\" claims " + std::to_string(size) +
             " bytes, more than the file holds");
      }
      // The attributes that size the chunk table.
      unsigned char value[16] = {};
      const size_t kept = std::min<size_t>(static_cast<size_t>(size), sizeof(value));
      if (!in.read(reinterpret_cast<char*>(value), static_cast<std::streamsize>(kept))) return;
      in.seekg(static_cast<std::streamoff>(at + static_cast<std::uintmax_t>(size)));
      if (name == "dataWindow" && type == "box2i" && size == 16) {
        claims.has_window = true;
        for (int i = 0; i < 4; ++i) {
          claims.window[i] = static_cast<int32_t>(little_endian_u32(value + 4 * i));
        }
      } else if (name == "tiles" && type == "tiledesc" && size == 9) {
        claims.tiled = true;
        claims.tile[0] = little_endian_u32(value);
        claims.tile[1] = little_endian_u32(value + 4);
        claims.level_mode = value[8] & 0x0f;
      } else if (name == "compression" && type == "compression" && size == 1) {
        claims.compression = value[0];
      } else if (name == "type" &&
                 (std::strncmp(reinterpret_cast<char*>(value), "tiledimage", 10) == 0 ||
                  std::strncmp(reinterpret_cast<char*>(value), "deeptile", 8) == 0)) {
        claims.tiled = true;
      }
    }
    if (attributes == 0) break;  // the empty header that ends a multi-part list
    if (claims.has_window) {
      const long long width = 1LL + claims.window[2] - claims.window[0];
      const long long height = 1LL + claims.window[3] - claims.window[1];
      if (width < 1 || height < 1 || width > limits::kImageSide || height > limits::kImageSide) {
        fail("part " + std::to_string(part) + " claims an image of " + std::to_string(width) +
             " x " + std::to_string(height) + " (each side must be 1 to " +
             std::to_string(limits::kImageSide) + ")");
      }
      chunks += chunks_of(claims);
    }
    if (!multipart) break;
  }
  if (8 * chunks > static_cast<long double>(bytes)) {
    fail("its header implies " + std::to_string(static_cast<long long>(chunks)) +
         " chunks, whose offsets alone need more than its " + std::to_string(bytes) + " bytes");
  }
}

void check_exr_pixels(const std::filesystem::path& file, const Imf::Header& header) {
  const Imath::Box2i window = header.dataWindow();
  const long long width = 1LL + window.max.x - window.min.x;
  const long long height = 1LL + window.max.y - window.min.y;
  if (width < 1 || height < 1 || width > limits::kImageSide || height > limits::kImageSide) {
    throw InputError(file.string() + ": an image of " + std::to_string(width) + " x " +
                     std::to_string(height) + " (each side must be 1 to " +
                     std::to_string(limits::kImageSide) + ")");
  }
  // Pixel (min.x, min.y) is addressed through a base pointer shifted by it: coordinates far from
  // 0 would overflow that arithmetic.
  constexpr long long kFar = 1LL << 30;
  for (const long long v : {window.min.x, window.min.y}) {
    if (v < -kFar || v > kFar) {
      throw InputError(file.string() + ": the data window starts at " + std::to_string(v) +
                       ", beyond +-2^30");
    }
  }
  long long channels = 0;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) ++channels;
  if (channels > limits::kImageChannels) {
    throw InputError(file.string() + ": " + std::to_string(channels) + " channels, more than " +
                     std::to_string(limits::kImageChannels));
  }
  // Float pixels as read, and read_exr's RGB copy in doubles.
  const double pixels = static_cast<double>(width) * static_cast<double>(height);
  const double need = pixels * (4.0 * static_cast<double>(channels) + 24.0);
  std::error_code error;
  const double file_bytes = static_cast<double>(std::filesystem::file_size(file, error));
  const double memory =
      static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGESIZE));
  if (need > std::max(limits::kImageFloorBytes, limits::kImageBytesPerFileByte * file_bytes) ||
      (memory > 0 && need > 0.5 * memory)) {
    throw InputError(file.string() + ": an image of " + std::to_string(width) + " x " +
                     std::to_string(height) + " x " + std::to_string(channels) +
                     " channels would take " +
                     std::to_string(static_cast<long long>(need / (1 << 20))) +
                     " MiB, more than its " + std::to_string(static_cast<long long>(file_bytes)) +
                     " bytes can hold or half of this machine's memory");
  }
}

}  // namespace rad
