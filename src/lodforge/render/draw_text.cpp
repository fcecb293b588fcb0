// Text uses stb_easy_font (Debian libstb-dev, header only, public domain): it
// turns a string into axis-aligned quads in a ~6 x 12 pixel cell, which are
// filled here as rectangles scaled by an integer factor. No font files, no
// antialiasing needed at these sizes.
#include "lodforge/render/draw_text.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace lodforge {
namespace {

// Printable ASCII only: a newline would start a second line inside one label.
std::string printable(const std::string& s) {
  std::string out = s;
  for (char& c : out)
    if (c < 32 || c > 126) c = '?';
  return out;
}

}  // namespace

int text_width(const std::string& text) {
  std::string copy = printable(text);  // stb_easy_font takes a non-const char*
  return stb_easy_font_width(copy.data());
}

void draw_text(Image& img, int x, int y, const std::string& text, int scale, const Vec3& color,
               int clip_x0, int clip_x1) {
  std::string copy = printable(text);
  // ~270 bytes per character on average (stb's estimate); be generous.
  std::vector<char> buffer(copy.size() * 600 + 64);
  const int quads = stb_easy_font_print(0, 0, copy.data(), nullptr, buffer.data(),
                                        static_cast<int>(buffer.size()));
  const std::uint8_t rgb[3] = {to_byte(color.x), to_byte(color.y), to_byte(color.z)};
  // Each quad is 4 vertices of 16 bytes: x, y, z as floats, then RGBA bytes.
  constexpr std::size_t kVertexBytes = 16;
  const auto vertex_xy = [&](std::size_t i) {
    float xy[2];
    std::memcpy(xy, buffer.data() + i * kVertexBytes, sizeof xy);
    return Vec2{xy[0], xy[1]};
  };
  for (std::size_t q = 0; q < static_cast<std::size_t>(std::max(quads, 0)); ++q) {
    const Vec2 first = vertex_xy(4 * q);
    float qx0 = first.x, qx1 = qx0, qy0 = first.y, qy1 = qy0;
    for (std::size_t k = 1; k < 4; ++k) {
      const Vec2 p = vertex_xy(4 * q + k);
      qx0 = std::min(qx0, p.x);
      qx1 = std::max(qx1, p.x);
      qy0 = std::min(qy0, p.y);
      qy1 = std::max(qy1, p.y);
    }
    const int px0 = std::max({0, clip_x0, x + static_cast<int>(std::lround(qx0 * scale))});
    const int px1 = std::min({img.width, clip_x1, x + static_cast<int>(std::lround(qx1 * scale))});
    const int py0 = std::max(0, y + static_cast<int>(std::lround(qy0 * scale)));
    const int py1 = std::min(img.height, y + static_cast<int>(std::lround(qy1 * scale)));
    for (int py = py0; py < py1; ++py)
      for (int px = px0; px < px1; ++px) {
        std::uint8_t* p = img.at(px, py);
        p[0] = rgb[0];
        p[1] = rgb[1];
        p[2] = rgb[2];
      }
  }
}

}  // namespace lodforge
