#include "lodforge/render/write_png.h"

#include <gtest/gtest.h>
#include <stb_image.h>

#include <fstream>
#include <iterator>
#include <memory>

#include "lodforge/core/error.h"
#include "lodforge/render/render_mesh.h"
#include "mesh/test_meshes.h"
#include "render/pixel_checks.h"

namespace lodforge {
namespace {

struct Decoded {
  int width = 0, height = 0, channels = 0;
  std::vector<std::uint8_t> rgba;
};

Decoded decode(const std::string& png) {
  Decoded d;
  std::unique_ptr<stbi_uc, void (*)(void*)> data(
      stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(png.data()),
                            static_cast<int>(png.size()), &d.width, &d.height, &d.channels, 4),
      stbi_image_free);
  if (data)
    d.rgba.assign(data.get(), data.get() + static_cast<std::size_t>(d.width) * d.height * 4);
  return d;
}

TEST(WritePng, EncodesLosslessly) {
  const Image img = render_mesh(test::make_seamed_sphere(), {.width = 37, .height = 23}).image;
  const Decoded d = decode(encode_png(img));
  ASSERT_EQ(d.width, 37);
  ASSERT_EQ(d.height, 23);
  EXPECT_EQ(d.rgba, img.pixels);
}

TEST(WritePng, WrittenFileDecodesToTheSameSize) {
  const Image img = render_mesh(test::make_centered_cube(), {.width = 150, .height = 100}).image;
  const std::string path = test::output_dir() + "/write_png_test.png";
  write_png(img, path);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  const Decoded d = decode(bytes);
  EXPECT_EQ(d.width, 150);
  EXPECT_EQ(d.height, 100);
  EXPECT_EQ(d.rgba, img.pixels);
}

TEST(WritePng, EmptyImageOrBadPathThrows) {
  EXPECT_THROW(encode_png(Image{}), DataError);
  EXPECT_THROW(write_png(Image(2, 2), "/nonexistent-dir/x.png"), DataError);
}

}  // namespace
}  // namespace lodforge
