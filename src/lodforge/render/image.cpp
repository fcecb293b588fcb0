#include "lodforge/render/image.h"

#include <algorithm>
#include <cstring>

namespace lodforge {

Image::Image(int w, int h, float r, float g, float b) : width(w), height(h) {
  assert(w >= 0 && h >= 0);
  pixels.resize(static_cast<std::size_t>(w) * h * 4);
  const std::uint8_t rgba[4] = {to_byte(r), to_byte(g), to_byte(b), 255};
  for (std::size_t i = 0; i < pixels.size(); i += 4) std::memcpy(&pixels[i], rgba, 4);
}

void Image::blit(const Image& src, int x, int y) {
  const int x0 = std::max(0, x), x1 = std::min(width, x + src.width);
  if (x0 >= x1) return;
  for (int row = std::max(0, y); row < std::min(height, y + src.height); ++row)
    std::memcpy(at(x0, row), src.at(x0 - x, row - y), static_cast<std::size_t>(x1 - x0) * 4);
}

}  // namespace lodforge
