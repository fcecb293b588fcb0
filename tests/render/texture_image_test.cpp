// Texture images: SFImage values and image files.
#include "lodforge/render/texture_image.h"

#include <gtest/gtest.h>

#include <fstream>
#include <vector>

#include "lodforge/core/error.h"
#include "lodforge/render/write_png.h"
#include "mesh/test_meshes.h"
#include "render/pixel_checks.h"

namespace lodforge {
namespace {

TEST(TextureImage, SfImageComponentsAndRowOrder) {
  // RGB, 2x2: the first row given is the bottom one.
  const Texture rgb =
      sfimage_texture(std::vector<std::int32_t>{2, 2, 3, 0xff0000, 0x00ff00, 0x0000ff, 0xffffff});
  ASSERT_EQ(rgb.image.width, 2);
  EXPECT_FALSE(rgb.intensity);
  const std::uint8_t* bottom_left = rgb.image.at(0, 1);
  EXPECT_EQ(bottom_left[0], 255);
  EXPECT_EQ(bottom_left[1], 0);
  EXPECT_EQ(bottom_left[3], 255);
  EXPECT_EQ(rgb.image.at(0, 0)[2], 255);  // top left blue
  // Grey + alpha; RGBA.
  const Texture ga = sfimage_texture(std::vector<std::int32_t>{1, 1, 2, 0x4080});
  EXPECT_TRUE(ga.intensity);
  EXPECT_EQ(ga.image.at(0, 0)[0], 0x40);
  EXPECT_EQ(ga.image.at(0, 0)[2], 0x40);
  EXPECT_EQ(ga.image.at(0, 0)[3], 0x80);
  const Texture rgba = sfimage_texture(std::vector<std::int32_t>{1, 1, 4, int(0x11223344)});
  EXPECT_EQ(rgba.image.at(0, 0)[1], 0x22);
  EXPECT_EQ(rgba.image.at(0, 0)[3], 0x44);
}

TEST(TextureImage, BadSfImageAndBadFilesThrowDataError) {
  EXPECT_THROW(sfimage_texture(std::vector<std::int32_t>{2, 2, 3, 1}), DataError);
  EXPECT_THROW(sfimage_texture(std::vector<std::int32_t>{1, 1, 5, 1}), DataError);
  EXPECT_THROW(sfimage_texture(std::vector<std::int32_t>{0, 1, 3}), DataError);
  const std::string dir = test::output_dir();
  std::ofstream(dir + "/not_an_image.png") << "hello";
  try {
    read_texture(dir + "/not_an_image.png");
    ADD_FAILURE() << "no exception";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("not_an_image.png"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_texture(dir + "/no_such_file.png"), DataError);
}

TEST(TextureImage, ReadsThePngItWrites) {
  Image img(3, 2, 0, 0, 1);
  img.at(2, 1)[0] = 200;
  const std::string path = test::output_dir() + "/texture_round_trip.png";
  write_png(img, path);
  const Texture t = read_texture(path);
  EXPECT_EQ(t.image.width, 3);
  EXPECT_EQ(t.image.height, 2);
  EXPECT_EQ(t.image.pixels, img.pixels);
}

}  // namespace
}  // namespace lodforge
