// The switching-distance formula and the behaviour of the original's Table B.5.
#include "lodforge/lod/switching_ranges.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lodforge {
namespace {

TEST(SwitchingRanges, FormulaOfTheSpec) {
  // d = k eps / (2 tan(alpha/2) p) + r
  RangeOptions o{.error_range = 0.02f, .camera_angle = 0.785398f};
  double d = switch_distance(0.01, 2.0, 0.5, o);
  EXPECT_NEAR(d, 2.0 * 0.01 / (2 * std::tan(0.785398 / 2) * 0.02) + 0.5, 1e-6);
}

TEST(SwitchingRanges, LowerErrorRangeGivesLargerDistances) {
  // Table B.5 (cow): 0.1 % -> 33.9 m, 2 % -> 2.83 m, 10 % -> 1.52 m for the first switch.
  std::vector<double> errors = {0.001, 0.002, 0.004, 0.008};
  auto fine = switching_ranges(errors, 1, 1, {.error_range = 0.001f});
  auto normal = switching_ranges(errors, 1, 1, {.error_range = 0.02f});
  auto coarse = switching_ranges(errors, 1, 1, {.error_range = 0.10f});
  for (std::size_t i = 0; i < errors.size(); ++i) {
    EXPECT_GT(fine[i], normal[i]);
    EXPECT_GT(normal[i], coarse[i]);
  }
  // Each level's distance grows with its error; doubling the error roughly
  // doubles the distance beyond the radius.
  for (std::size_t i = 1; i < errors.size(); ++i) {
    EXPECT_GT(normal[i], normal[i - 1]);
    EXPECT_NEAR((normal[i] - 1) / (normal[i - 1] - 1), 2.0, 1e-4);
  }
}

TEST(SwitchingRanges, NonMonotoneErrorsStillGiveIncreasingRanges) {
  std::vector<double> errors = {0.02, 0.01, 0.01, 0.03};
  auto r = switching_ranges(errors, 1, 0, {});
  ASSERT_EQ(r.size(), 4u);
  for (std::size_t i = 1; i < r.size(); ++i) EXPECT_LT(r[i - 1], r[i]);
  EXPECT_FLOAT_EQ(r[0], float(switch_distance(0.02, 1, 0, {})));
}

TEST(SwitchingRanges, ScaleOfTheTransformScalesTheDistance) {
  double a = switch_distance(0.1, 1, 0, {});
  double b = switch_distance(0.1, 3, 0, {});
  EXPECT_NEAR(b, 3 * a, 1e-9);
}

}  // namespace
}  // namespace lodforge
