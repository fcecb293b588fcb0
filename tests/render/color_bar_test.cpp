// A colour scale beside a picture.
#include "lodforge/render/color_bar.h"

#include <gtest/gtest.h>

#include "mesh/test_meshes.h"
#include "render/pixel_checks.h"

namespace lodforge {
namespace {

TEST(ColorBar, WidensThePictureAndRunsFromMinAtTheBottomToMaxAtTheTop) {
  const Image picture(100, 240, 1, 1, 1);
  const Image out = add_color_bar(
      picture, {.stops = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}}, .min = 0, .max = 2.5, .title = "dev"});
  EXPECT_EQ(out.height, picture.height);
  ASSERT_GT(out.width, picture.width + 30);
  // The bar's column: blue near the bottom, green in the middle, red near the top.
  const int x = picture.width + 10;
  EXPECT_TRUE(test::shaded_like(out.at(x, 230), {0, 0, 1}, 0.1));
  EXPECT_TRUE(test::shaded_like(out.at(x, 125), {0, 1, 0}, 0.1));
  EXPECT_TRUE(test::shaded_like(out.at(x, 20), {1, 0, 0}, 0.1));
  // Labels: dark text pixels right of the bar.
  int dark = 0;
  for (int y = 0; y < out.height; ++y)
    for (int xx = x + 20; xx < out.width; ++xx)
      if (out.at(xx, y)[0] < 64) ++dark;
  EXPECT_GT(dark, 50);
}

}  // namespace
}  // namespace lodforge
