#include "lodforge/mcoctree/sign_components.h"

#include <gtest/gtest.h>

namespace lodforge {
namespace {

constexpr std::uint8_t kIn = 1, kOther = 4;

struct Grid {
  std::array<std::int64_t, 3> dim{20, 16, 12};
  std::vector<std::uint8_t> state = std::vector<std::uint8_t>(20 * 16 * 12, kOther);
  std::uint8_t& at(int x, int y, int z) { return state[x + dim[0] * (y + dim[1] * z)]; }
  void box(int x0, int x1, int y0, int y1, int z0, int z1, bool inside) {
    for (int z = z0; z < z1; ++z)
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
          at(x, y, z) = static_cast<std::uint8_t>(inside ? at(x, y, z) | kIn : at(x, y, z) & ~kIn);
  }
};

// A solid block with a void inside and a tunnel to the outside elsewhere, a
// stray blob of 2x2x2 points, and a second solid part of 3x3x3 (27 points).
TEST(CleanScanSigns, FillsVoidsDropsBubblesKeepsParts) {
  Grid g;
  g.box(2, 12, 2, 12, 2, 10, true);   // 800 points
  g.box(5, 8, 5, 8, 4, 7, false);     // a void of 27 points, enclosed
  g.box(9, 11, 0, 6, 5, 6, false);    // a groove from the border into the block
  g.box(15, 17, 3, 5, 3, 5, true);    // a blob of 8 points
  g.box(14, 17, 10, 13, 6, 9, true);  // a part of 27 points
  auto out = detail::clean_scan_signs(g.state, g.dim, kIn, 10, 0.01);
  EXPECT_EQ(out.filled_voids, 1u);
  EXPECT_EQ(out.filled_points, 27u);
  EXPECT_EQ(out.dropped_parts, 1u);
  EXPECT_EQ(out.dropped_points, 8u);
  EXPECT_TRUE(g.at(6, 6, 5) & kIn);    // the void is filled
  EXPECT_FALSE(g.at(10, 3, 5) & kIn);  // the groove reaches the border: kept
  EXPECT_FALSE(g.at(15, 3, 3) & kIn);  // the blob is gone
  EXPECT_TRUE(g.at(15, 11, 7) & kIn);  // the part stays
  EXPECT_FALSE(g.at(0, 0, 0) & kIn);
  for (auto s : g.state) EXPECT_TRUE(s & kOther);  // other bits untouched

  // The fraction: the 27-point part is below 5 % of the block's 792 points.
  Grid h = g;
  out = detail::clean_scan_signs(h.state, h.dim, kIn, 10, 0.05);
  EXPECT_EQ(out.dropped_parts, 1u);
  EXPECT_FALSE(h.at(15, 11, 7) & kIn);
  // A clean lattice is left as it is.
  Grid c = g;
  out = detail::clean_scan_signs(c.state, c.dim, kIn, 10, 0.01);
  EXPECT_EQ(out.filled_voids + out.dropped_parts, 0u);
  EXPECT_EQ(c.state, g.state);
}

}  // namespace
}  // namespace lodforge
