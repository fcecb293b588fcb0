// Texture images: files decoded by stb_image (Debian's libstb, linked like
// stb_image_write in write_png.cpp, so no translation unit here defines
// STB_IMAGE_IMPLEMENTATION), and VRML 1.0 SFImage values.
#include "lodforge/render/texture_image.h"

#include <fmt/core.h>
#include <stb_image.h>

#include <algorithm>
#include <climits>
#include <memory>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"

namespace lodforge {
namespace {

constexpr int kMaxSide = 16384;

}  // namespace

Texture read_texture(const std::string& path) {
  const std::string bytes = read_file(path);
  return decode_texture(
      std::span(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()), path);
}

Texture decode_texture(std::span<const unsigned char> bytes, const std::string& name) {
  if (bytes.size() > std::size_t(INT_MAX))
    throw DataError(fmt::format("{}: the image file is too large", name));
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  int w = 0, h = 0, components = 0;
  // The size first, so a huge image is refused before it is decoded.
  if (!stbi_info_from_memory(data, size, &w, &h, &components))
    throw DataError(fmt::format("{}: not an image this reader decodes ({})", name,
                                stbi_failure_reason() ? stbi_failure_reason() : "unknown format"));
  if (w < 1 || h < 1 || w > kMaxSide || h > kMaxSide)
    throw DataError(
        fmt::format("{}: image of {}x{} pixels; at most {} a side are read", name, w, h, kMaxSide));
  const std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(data, size, &w, &h, &components, 4), stbi_image_free);
  if (!pixels)
    throw DataError(fmt::format("{}: the image cannot be decoded ({})", name,
                                stbi_failure_reason() ? stbi_failure_reason() : "unknown error"));
  Texture t;
  t.image = Image(w, h);
  t.image.pixels.assign(pixels.get(), pixels.get() + std::size_t(w) * std::size_t(h) * 4);
  t.intensity = components <= 2;
  return t;
}

Texture sfimage_texture(std::span<const std::int32_t> values) {
  if (values.size() < 3) throw DataError("SFImage: no width, height and components");
  const std::int32_t w = values[0], h = values[1], n = values[2];
  if (w < 1 || h < 1 || w > kMaxSide || h > kMaxSide)
    throw DataError(fmt::format("SFImage of {}x{} pixels; 1..{} a side are drawn", w, h, kMaxSide));
  if (n < 1 || n > 4)
    throw DataError(fmt::format("SFImage with {} components; 1..4 are defined", n));
  const std::size_t count = std::size_t(w) * std::size_t(h);
  if (values.size() - 3 < count)
    throw DataError(
        fmt::format("SFImage of {}x{} pixels has {} pixel values", w, h, values.size() - 3));
  Texture t;
  t.image = Image(w, h);
  t.intensity = n <= 2;
  for (std::size_t i = 0; i < count; ++i) {
    const auto v = static_cast<std::uint32_t>(values[3 + i]);
    std::uint8_t c[4];
    for (int k = 0; k < n; ++k) c[k] = static_cast<std::uint8_t>(v >> (8 * (n - 1 - k)));
    // Grey (+ alpha) spreads to RGB; an image without alpha is opaque.
    const std::uint8_t rgba[4] = {c[0], n >= 3 ? c[1] : c[0], n >= 3 ? c[2] : c[0],
                                  n == 2   ? c[1]
                                  : n == 4 ? c[3]
                                           : std::uint8_t(255)};
    // SFImage rows go from the bottom up; Image rows from the top down.
    const int x = int(i % std::size_t(w)), y = h - 1 - int(i / std::size_t(w));
    std::copy(rgba, rgba + 4, t.image.at(x, y));
  }
  return t;
}

}  // namespace lodforge
