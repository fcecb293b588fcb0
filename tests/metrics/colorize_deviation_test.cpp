#include "lodforge/metrics/colorize_deviation.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lodforge {
namespace {

TriangleMesh points(std::size_t n) {
  TriangleMesh m;
  m.positions.resize(n);
  return m;
}

TEST(ColorizeDeviation, BlueGreenRedScale) {
  std::vector<float> v{0, 0.5f, 1, 0.25f, 0.75f, 2, -1, std::nanf("")};
  auto c = colorize_deviation(points(v.size()), v, 1);
  ASSERT_EQ(c.size(), v.size());
  EXPECT_EQ(c[0], (Vec3{0, 0, 1}));        // 0: blue
  EXPECT_EQ(c[1], (Vec3{0, 1, 0}));        // half: green
  EXPECT_EQ(c[2], (Vec3{1, 0, 0}));        // max: red
  EXPECT_EQ(c[3], (Vec3{0, 0.5f, 0.5f}));  // linear between
  EXPECT_EQ(c[4], (Vec3{0.5f, 0.5f, 0}));
  EXPECT_EQ(c[5], (Vec3{1, 0, 0}));  // above max: clamped
  EXPECT_EQ(c[6], (Vec3{0, 0, 1}));  // below 0: clamped
  EXPECT_EQ(c[7], (Vec3{0, 0, 1}));  // NaN: blue
}

TEST(ColorizeDeviation, ZeroMaxIsAllBlue) {
  std::vector<float> v{0, 0, 0};
  for (const auto& c : colorize_deviation(points(3), v, 0)) EXPECT_EQ(c, (Vec3{0, 0, 1}));
}

}  // namespace
}  // namespace lodforge
