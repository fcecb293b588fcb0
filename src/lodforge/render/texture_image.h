#pragma once
/// Texture images for the rasteriser: image files (PNG, JPEG, GIF, BMP, TGA,
/// PNM, PSD, HDR: what stb_image reads) and VRML 1.0 SFImage values.
#include <cstdint>
#include <span>
#include <string>

#include "lodforge/render/image.h"

namespace lodforge {

struct Texture {
  /// RGBA, rows from the top of the picture down: texture coordinate t = 1
  /// is the top row, t = 0 the bottom one, s = 0 the left column.
  Image image;
  /// One- or two-component image (grey, grey + alpha): it scales the
  /// surface's colour instead of replacing it (VRML lighting model).
  bool intensity = false;
  bool repeat_s = true;  ///< wrap s (else clamp to the edge)
  bool repeat_t = true;  ///< wrap t (else clamp to the edge)
  /// An RGB texel scales the surface colour instead of replacing it (glTF).
  bool modulates = false;
  float alpha_cutoff = 0.5f;  ///< texels of alpha below this are holes
};

/// Reads an image file (gzip-compressed too, like every reader). Throws
/// DataError naming the file when it cannot be read, is not an image
/// stb_image decodes, or is larger than 16384 pixels a side.
Texture read_texture(const std::string& path);

/// As read_texture, from an image file's bytes in memory (a glTF file's
/// embedded images); `name` names it in the errors.
Texture decode_texture(std::span<const unsigned char> bytes, const std::string& name);

/// The texture of an SFImage value: width, height, components (1..4), then
/// width * height pixels, each one integer holding its components from the
/// most significant byte down (0xFF0000 is red in an RGB image), from the
/// bottom row up. Throws DataError for a size out of 1..16384, components
/// out of 1..4 or too few pixels.
Texture sfimage_texture(std::span<const std::int32_t> values);

}  // namespace lodforge
