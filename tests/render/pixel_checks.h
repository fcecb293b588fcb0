#pragma once
// Pixel statistics shared by the render tests.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>

#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/render/image.h"

namespace lodforge::test {

struct PixelStats {
  double covered_fraction = 0;  ///< pixels differing from the background
  std::size_t distinct_colors = 0;
  double mean_r = 0, mean_g = 0, mean_b = 0;  ///< over covered pixels, 0..255
  double center_x = 0, center_y = 0;          ///< centroid of covered pixels, in pixels
};

/// Statistics over the rectangle [x0, x0 + w) x [y0, y0 + h) of `img`
/// (the whole image by default); background = the colour of the image's top-left pixel.
inline PixelStats pixel_stats(const Image& img, int x0 = 0, int y0 = 0, int w = -1, int h = -1) {
  if (w < 0) w = img.width;
  if (h < 0) h = img.height;
  const std::uint8_t* bg = img.at(0, 0);
  const std::uint32_t bg_key = bg[0] << 16 | bg[1] << 8 | bg[2];
  PixelStats s;
  std::set<std::uint32_t> colors;
  std::size_t covered = 0;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) {
      const std::uint8_t* p = img.at(x, y);
      const std::uint32_t key = p[0] << 16 | p[1] << 8 | p[2];
      colors.insert(key);
      if (key == bg_key) continue;
      ++covered;
      s.mean_r += p[0];
      s.mean_g += p[1];
      s.mean_b += p[2];
      s.center_x += x + 0.5;
      s.center_y += y + 0.5;
    }
  s.distinct_colors = colors.size();
  s.covered_fraction = static_cast<double>(covered) / (static_cast<double>(w) * h);
  if (covered) {
    for (double* v : {&s.mean_r, &s.mean_g, &s.mean_b, &s.center_x, &s.center_y})
      *v /= static_cast<double>(covered);
  }
  return s;
}

/// True if the RGB bytes `p` are `rgb` (in [0,1]) lit by some amount: their
/// chromaticities (each channel over the sum) are within `tolerance`, and
/// the pixel is not black. Lighting scales a colour; it keeps its hue.
inline bool shaded_like(const std::uint8_t* p, Vec3 rgb, double tolerance = 0.06) {
  const double sum = double(p[0]) + p[1] + p[2], want = double(rgb.x) + rgb.y + rgb.z;
  if (sum < 30 || want <= 0) return false;
  return std::abs(p[0] / sum - rgb.x / want) < tolerance &&
         std::abs(p[1] / sum - rgb.y / want) < tolerance &&
         std::abs(p[2] / sum - rgb.z / want) < tolerance;
}

/// Fraction of the pixels of `img` that differ from its top-left (background)
/// pixel and are shaded_like `rgb`.
inline double fraction_shaded_like(const Image& img, Vec3 rgb, double tolerance = 0.06) {
  const std::uint8_t* bg = img.at(0, 0);
  std::size_t n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = img.at(x, y);
      if (p[0] == bg[0] && p[1] == bg[1] && p[2] == bg[2]) continue;
      if (shaded_like(p, rgb, tolerance)) ++n;
    }
  return double(n) / (double(img.width) * img.height);
}

/// Fraction of pixels that differ between two images of the same size.
inline double difference_fraction(const Image& a, const Image& b) {
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.pixels.size(); i += 4)
    if (a.pixels[i] != b.pixels[i] || a.pixels[i + 1] != b.pixels[i + 1] ||
        a.pixels[i + 2] != b.pixels[i + 2])
      ++differ;
  return static_cast<double>(differ) / static_cast<double>(a.pixels.size() / 4);
}

/// Directory for pictures a person may look at after the tests ran (created).
inline std::string output_dir() {
  const std::string dir = std::string(LODFORGE_BINARY_DIR) + "/render_test_output";
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace lodforge::test
