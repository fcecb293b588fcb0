// What every simplifier shares: the triangle target and the input check.
#include "lodforge/simplify/simplify_result.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "lodforge/core/error.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

using ::testing::ThrowsMessage;

TEST(SimplifyResult, TriangleTargetIsTheSmallerOfCountAndRatio) {
  EXPECT_EQ(SimplifyTarget{}.triangle_target(100), 100u);  // no reduction asked
  EXPECT_EQ((SimplifyTarget{.triangles = 30}.triangle_target(100)), 30u);
  EXPECT_EQ((SimplifyTarget{.triangles = 300}.triangle_target(100)), 100u);
  SimplifyTarget ratio;
  ratio.ratio = 0.25f;
  EXPECT_EQ(ratio.triangle_target(101), 25u);  // rounded down
  ratio.triangles = 20;
  EXPECT_EQ(ratio.triangle_target(101), 20u);
  ratio.triangles = 40;
  EXPECT_EQ(ratio.triangle_target(101), 25u);
}

TEST(SimplifyResult, StopReasonsHaveTheirWords) {
  EXPECT_STREQ(to_string(StopReason::kTargetReached), "target reached");
  EXPECT_STREQ(to_string(StopReason::kErrorBudgetReached), "error budget reached");
  EXPECT_STREQ(to_string(StopReason::kCannotSimplify), "cannot simplify further");
  EXPECT_STREQ(to_string(StopReason::kNoReduction), "no reduction asked");
}

TEST(SimplifyResult, InputCheckNamesTheBadIndexOrPoint) {
  TriangleMesh m = test::make_tetrahedron();
  EXPECT_NO_THROW(check_simplify_input(m, "qem"));
  m.triangles[2][1] = 4;
  EXPECT_THAT([&] { check_simplify_input(m, "qem"); },
              ThrowsMessage<DataError>("qem: triangle index 4 out of range (4 vertices)"));
  m = test::make_tetrahedron();
  m.lines.push_back({0, 7});
  EXPECT_THAT([&] { check_simplify_input(m, "cluster"); },
              ThrowsMessage<DataError>("cluster: line index 7 out of range (4 vertices)"));
  m = test::make_tetrahedron();
  m.positions[3].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THAT([&] { check_simplify_input(m, "qem"); },
              ThrowsMessage<DataError>("qem: vertex 3 has a coordinate that is not finite"));
}

}  // namespace
}  // namespace lodforge
