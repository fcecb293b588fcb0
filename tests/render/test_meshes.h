#pragma once
// Small named meshes and pixel statistics shared by the render tests.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>

#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/render/image.h"

namespace lodforge::test {

/// Axis-aligned cube [-h, h]^3 around `center`, 8 shared vertices, 12
/// counter-clockwise triangles seen from outside.
inline TriangleMesh cube(float h = 1, Vec3 center = {}) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.push_back(center + Vec3{(i & 1) ? h : -h, (i & 2) ? h : -h, (i & 4) ? h : -h});
  // Quads as (a, b, c, d) counter-clockwise from outside.
  const std::uint32_t quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

/// UV sphere of radius r: `rings` latitude bands, `segments` longitude bands.
/// Like many real meshes it repeats vertices: a ring of copies at each pole and
/// a seam at longitude 0, at exactly equal positions.
inline TriangleMesh sphere(float r = 1, int rings = 24, int segments = 48) {
  TriangleMesh m;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i <= rings; ++i) {
    const double theta = pi * i / rings;  // from +Y down
    const double ring_r = (i == 0 || i == rings) ? 0 : r * std::sin(theta);
    for (int j = 0; j <= segments; ++j) {
      const double phi = 2 * pi * (j % segments) / segments;
      m.positions.push_back({static_cast<float>(ring_r * std::sin(phi)),
                             static_cast<float>(r * std::cos(theta)),
                             static_cast<float>(ring_r * std::cos(phi))});
    }
  }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * (segments + 1) + j); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      if (i > 0) m.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
      if (i < rings - 1) m.triangles.push_back({at(i, j + 1), at(i + 1, j), at(i + 1, j + 1)});
    }
  return m;
}

/// The same surface as a triangle soup: three vertices of its own per triangle.
inline TriangleMesh soup(const TriangleMesh& m) {
  TriangleMesh s;
  for (const auto& t : m.triangles) {
    const auto base = static_cast<std::uint32_t>(s.positions.size());
    for (auto i : t) s.positions.push_back(m.positions[i]);
    s.triangles.push_back({base, base + 1, base + 2});
  }
  return s;
}

/// Gives every vertex one colour.
inline TriangleMesh colored(TriangleMesh m, Vec3 rgb) {
  m.colors.assign(m.positions.size(), rgb);
  return m;
}

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
