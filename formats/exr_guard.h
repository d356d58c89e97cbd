#pragma once
/// Checks an OpenEXR file before and after OpenEXR reads its header, so that a small file cannot
/// make the reader allocate gigabytes (issue 16). OpenEXR 3.1 allocates each header attribute at
/// the size the file states (an attribute of a type it does not know included) and its table of
/// chunk offsets from the data window and tiles, before it reads them; the fuzzer found files
/// of a few hundred bytes that made it allocate up to 2 GB.
#include <ImfForward.h>

#include <filesystem>

namespace rad {

/// Before OpenEXR opens the file: walks the header(s) (every part of a multi-part file) and
/// throws InputError naming the file when an attribute claims more bytes than the file has, or
/// when the table of chunk offsets the data window, tiles and compression imply cannot fit in
/// the file (8 bytes an entry), or a data window side exceeds limits::kImageSide. What it cannot
/// parse it leaves to OpenEXR, which reports it. Cost: reads the header only.
void check_exr_claims(const std::filesystem::path& file);

/// After OpenEXR has read the header: the pixels it claims against limits::kImageSide,
/// kImageChannels, kImageBytesPerFileByte (with kImageFloorBytes) and half the machine's memory,
/// before they are allocated.
void check_exr_pixels(const std::filesystem::path& file, const Imf::Header& header);

}  // namespace rad
