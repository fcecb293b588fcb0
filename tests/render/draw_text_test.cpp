// Labels in pictures: text drawn in its colour inside its cell, scaled by an
// integer factor, clipped to the image and to a column range.
#include "lodforge/render/draw_text.h"

#include <gtest/gtest.h>

namespace lodforge {
namespace {

// The box of pixels whose red byte is set (x0, y0, x1, y1; x1 < x0 if none)
// in columns [from, to).
std::array<int, 4> ink(const Image& img, int from = 0, int to = INT_MAX) {
  std::array<int, 4> box{INT_MAX, INT_MAX, -1, -1};
  for (int y = 0; y < img.height; ++y)
    for (int x = std::max(from, 0); x < std::min(to, img.width); ++x)
      if (img.at(x, y)[0] > 0) {
        box = {std::min(box[0], x), std::min(box[1], y), std::max(box[2], x), std::max(box[3], y)};
      }
  return box;
}

TEST(DrawText, InkStaysInTheCellAndScales) {
  const int w = text_width("Level 3");
  EXPECT_GT(w, 6 * 5);  // about six font pixels a character
  EXPECT_LT(w, 6 * 9);
  Image one(200, 60), two(200, 60);
  draw_text(one, 10, 5, "Level 3", 1, {1, 0, 0});
  draw_text(two, 10, 5, "Level 3", 2, {1, 0, 0});
  const auto a = ink(one), b = ink(two);
  ASSERT_GE(a[2], a[0]) << "nothing drawn";
  EXPECT_GE(a[0], 10);
  EXPECT_GE(a[1], 5);
  EXPECT_LE(a[2], 10 + w);
  EXPECT_LE(a[3], 5 + kTextLineHeight);
  // Twice the scale: twice the extent (within a font pixel).
  EXPECT_NEAR(b[2] - 10, 2 * (a[2] - 10), 2);
  EXPECT_NEAR(b[3] - 5, 2 * (a[3] - 5), 2);
  // Drawn in its colour, nothing else touched.
  EXPECT_EQ(one.at(a[0], a[1])[1], 0);
  for (int x = 0; x < 10; ++x) EXPECT_EQ(one.at(x, 10)[0], 0);
}

TEST(DrawText, ClippedToTheImageAndColumns) {
  Image img(40, 20);
  // Off every edge: no crash, ink only inside.
  draw_text(img, -15, -4, "clipped text", 3, {1, 0, 0});
  EXPECT_GE(ink(img)[2], 0);
  Image columns(200, 30);
  draw_text(columns, 0, 0, "abcdefghijklmnop", 2, {1, 0, 0}, 20, 60);
  EXPECT_LT(ink(columns, 0, 20)[2], 0);    // nothing left of the range
  EXPECT_LT(ink(columns, 60, 200)[2], 0);  // nothing right of it
  EXPECT_GE(ink(columns, 20, 60)[2], 20);
  // A character outside printable ASCII is drawn (as '?'), not skipped.
  EXPECT_EQ(text_width("a\nb"), text_width("a?b"));
}

}  // namespace
}  // namespace lodforge
