#pragma once
/// @file
/// PNG files for `Image`s (libpng): frames and stills to disk, and back for tests and tools.

#include <filesystem>

#include "mjarm/file_writer.hpp"
#include "mjarm/render/image.hpp"

namespace mjarm {

/// Writes @p image as an 8-bit RGB PNG at @p path (overwritten when it exists).
/// @throws Error naming the path when the image is empty or inconsistent (rgb.size() ≠
///         width·height·3) or when the file cannot be written (missing folder, no permission,
///         full disk).
void write_png(const Image& image, const std::filesystem::path& path);

/// Encodes @p image as an 8-bit RGB PNG into @p file without committing it: the caller commits
/// the file (or drops it, which removes its temporary file and keeps the old one).
/// @throws Error as above; @p file then holds a partial PNG and must not be committed.
void write_png(const Image& image, FileWriter& file);

/// Reads a PNG file (any bit depth or colour type) as 8-bit RGB; alpha is dropped, grey is
/// expanded to three channels.
/// @throws Error naming the path when it is missing or not a valid PNG.
Image read_png(const std::filesystem::path& path);

}  // namespace mjarm
