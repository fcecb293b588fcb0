// The RGBA picture: filling with a colour, and blitting clipped to the edges.
#include "lodforge/render/image.h"

#include <gtest/gtest.h>

#include <array>

namespace lodforge {
namespace {

std::array<int, 4> pixel(const Image& im, int x, int y) {
  const std::uint8_t* p = im.at(x, y);
  return {p[0], p[1], p[2], p[3]};
}

TEST(Image, FillsWithOneOpaqueColourRoundedAndClamped) {
  const Image im(3, 2, 1.f, 0.5f, -2.f);
  EXPECT_FALSE(im.empty());
  ASSERT_EQ(im.pixels.size(), 3u * 2u * 4u);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) EXPECT_EQ(pixel(im, x, y), (std::array<int, 4>{255, 128, 0, 255}));
  EXPECT_TRUE(Image().empty());
  EXPECT_TRUE(Image(0, 4).empty());
  EXPECT_EQ(to_byte(2.f), 255);
}

TEST(Image, BlitIsClippedToTheDestination) {
  Image dst(4, 3);  // black
  const Image src(2, 2, 1, 1, 1);
  dst.blit(src, 3, -1);  // only src's bottom-left pixel lands, at (3, 0)
  const std::array<int, 4> white{255, 255, 255, 255}, black{0, 0, 0, 255};
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_EQ(pixel(dst, x, y), x == 3 && y == 0 ? white : black);
  dst.blit(src, -5, 0);  // wholly outside: nothing
  dst.blit(src, 0, 7);
  EXPECT_EQ(pixel(dst, 0, 0), black);
  // Rows keep their place: a two-colour source lands row by row.
  Image two(1, 2, 1, 0, 0);
  two.at(0, 1)[1] = 255;
  dst.blit(two, 1, 1);
  EXPECT_EQ(pixel(dst, 1, 1), (std::array<int, 4>{255, 0, 0, 255}));
  EXPECT_EQ(pixel(dst, 1, 2), (std::array<int, 4>{255, 255, 0, 255}));
}

}  // namespace
}  // namespace lodforge
