#pragma once
/// The limits on what a user's files may ask for, in one place: beyond them a reader stops with
/// one line naming the file and the limit, before it allocates (issue 16: a small hostile file
/// must not crash the process or claim gigabytes). Each is far above any real scene: the
/// bundled Cornell box has 36 polygons, 8k elements and a 512 x 512 camera.
#include <cstdint>

namespace rad::limits {

/// JSON nesting (arrays and objects inside each other); a scene needs 6.
inline constexpr int kJsonDepth = 64;
/// Size of a scene file (JSON) and of a mesh file or points CSV, in bytes.
inline constexpr std::uintmax_t kSceneFileBytes = std::uintmax_t{256} << 20;
inline constexpr std::uintmax_t kMeshFileBytes = std::uintmax_t{2} << 30;
/// Polygons in a scene (after meshes are read) and vertices in one polygon.
inline constexpr long long kPolygons = 10'000'000;
inline constexpr long long kPolygonVertices = 100'000;
/// Vertices in one mesh file (three per polygon at most, in a soup of triangles).
inline constexpr long long kMeshVertices = 3 * kPolygons;
/// Image side in pixels: the command line's --width/--height limit and the scene camera's.
inline constexpr int kImageSide = 1 << 15;
/// An OpenEXR image `compare` reads: its channels, and the bytes of pixels it may claim per byte
/// of file (as read: 4 per channel and 24 for the RGB copy) above a floor of 1 MiB. Lossless
/// OpenEXR compressions stop near 1032:1 (ZIP's deflate; RLE 64:1, PIZ 32:1), so every image
/// `render` writes passes; only a lossy DWA file of an almost constant image could exceed it.
/// With the image side above and half the machine's memory, these are checked before pixels
/// are allocated.
inline constexpr int kImageChannels = 64;
inline constexpr double kImageBytesPerFileByte = 4096;
inline constexpr double kImageFloorBytes = 1 << 20;
/// Elements in a solution file (the counts its XML claims are checked against it before VTK
/// allocates: points and cells up to 4 per element, array tuples up to 8).
inline constexpr long long kSolutionElements = 5'000'000;

/// A vertex coordinate's magnitude: beyond it, lengths and areas of the scene overflow (a
/// polygon at +-1e200 read as "1 distinct vertex").
inline constexpr double kCoordinate = 1e100;

/// The power a scene's lights may emit in all, in W (per channel): the polygons' emission times
/// their area and 4 pi times each point light's intensity. The Sun's is 4e26 W; at 1e100 the
/// squares and sums the solver and the bounds take of it stay far from overflowing (emission
/// 1e300 made infinite pixels; 1.7e308 stopped the solver after two shots claiming 0% unshot).
inline constexpr double kPower = 1e100;

}  // namespace rad::limits
