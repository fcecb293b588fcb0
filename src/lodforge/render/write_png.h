#pragma once
/// PNG files of images (8-bit RGBA), encoded with stb_image_write.
#include <string>

#include "lodforge/render/image.h"

namespace lodforge {

/// The bytes of a PNG file holding `image`. Throws DataError if the image is
/// empty or the encoder fails.
std::string encode_png(const Image& image);

/// Writes `image` as a PNG file atomically (temporary file, then rename; "-"
/// writes to standard output). Throws DataError if it cannot be written.
void write_png(const Image& image, const std::string& path);

}  // namespace lodforge
