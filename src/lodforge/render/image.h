#pragma once
/// An 8-bit RGBA picture, the output of the renderers and the input of write_png.
#include <cassert>
#include <cmath>
#include <cstdint>
#include <vector>

namespace lodforge {

struct Image {
  int width = 0;
  int height = 0;
  /// width * height * 4 bytes: R, G, B, A per pixel, rows from the top of the
  /// picture down (the order PNG files use), pixels left to right.
  std::vector<std::uint8_t> pixels;

  Image() = default;
  /// A width x height picture filled with one opaque colour (RGB in [0,1]).
  Image(int w, int h, float r = 0, float g = 0, float b = 0);

  bool empty() const { return width <= 0 || height <= 0; }
  /// The 4 bytes of pixel (x, y); (0, 0) is the top-left corner.
  std::uint8_t* at(int x, int y) {
    assert(x >= 0 && x < width && y >= 0 && y < height);
    return pixels.data() + (static_cast<std::size_t>(y) * width + x) * 4;
  }
  const std::uint8_t* at(int x, int y) const {
    assert(x >= 0 && x < width && y >= 0 && y < height);
    return pixels.data() + (static_cast<std::size_t>(y) * width + x) * 4;
  }
  /// Copies `src` with its top-left corner at (x, y), clipped to this image.
  void blit(const Image& src, int x, int y);
};

/// An 8-bit channel value from a float in [0,1] (clamped, rounded).
inline std::uint8_t to_byte(float v) {
  v = v < 0 ? 0 : (v > 1 ? 1 : v);
  return static_cast<std::uint8_t>(std::lround(v * 255.f));
}

}  // namespace lodforge
