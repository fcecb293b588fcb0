#include "lodforge/core/quadric.h"

#include <gtest/gtest.h>

namespace lodforge {
namespace {

TEST(Quadric, ZeroInitialisedIsTheZeroForm) {
  Quadric q{};
  EXPECT_EQ(q(1, 2, 3), 0.0);
}

TEST(Quadric, PlaneGivesWeightedSquaredDistance) {
  // The plane z = 2 (n = (0, 0, 1), d = -2) with weight 3.
  Quadric q = Quadric::plane(0, 0, 1, -2, 3);
  EXPECT_DOUBLE_EQ(q(5, -7, 2), 0.0);
  EXPECT_DOUBLE_EQ(q(0, 0, 4), 3 * 4.0);
  EXPECT_DOUBLE_EQ(q(1, 1, 0), 3 * 4.0);
}

TEST(Quadric, SumOfPlanesIsSumOfDistances) {
  // x = 1 and y = -1: at (3, 3, 9) the squared distances are 4 and 16.
  Quadric q{};
  q.add_plane(1, 0, 0, -1, 1);
  q += Quadric::plane(0, 1, 0, 1, 1);
  EXPECT_DOUBLE_EQ(q(3, 3, 9), 20.0);
  EXPECT_DOUBLE_EQ((Quadric::plane(1, 0, 0, -1, 1) + Quadric::plane(0, 1, 0, 1, 1))(3, 3, 9), 20.0);
}

TEST(Quadric, UnnormalisedNormalScalesWithItsSquaredLength) {
  // 2x - 2 = 0 is the plane x = 1 with |n|^2 = 4.
  EXPECT_DOUBLE_EQ(Quadric::plane(2, 0, 0, -2, 1)(3, 0, 0), 4 * 4.0);
}

TEST(Quadric, NeverNegative) {
  // A point on the plane whose evaluation rounds below zero is clamped.
  Quadric q = Quadric::plane(0.1, 0.7, 0.3, -0.123456789, 1e6);
  EXPECT_GE(q(1.234567, 0.0, 0.0), 0.0);
  EXPECT_GE(q(0, 0.123456789 / 0.7, 0), 0.0);
}

TEST(QuadricMinimum, CornerOfThreePlanesIsExact) {
  // x = 1, y = 2, z = 3: full rank, the minimum is their common point
  // (regularisation pulls it towards x0 by lambda / (1 + lambda) = 0.3 %).
  Quadric q = Quadric::plane(1, 0, 0, -1, 1) + Quadric::plane(0, 1, 0, -2, 1) +
              Quadric::plane(0, 0, 1, -3, 1);
  const auto m = quadric_minimum(q, {1, 2, 3});
  EXPECT_DOUBLE_EQ(m[0], 1.0);
  EXPECT_DOUBLE_EQ(m[1], 2.0);
  EXPECT_DOUBLE_EQ(m[2], 3.0);
  const auto n = quadric_minimum(q, {0, 0, 0});
  EXPECT_NEAR(n[0], 1.0, 0.004);
  EXPECT_NEAR(n[2], 3.0, 0.01);
}

TEST(QuadricMinimum, FlatDirectionsKeepTheStartingPoint) {
  // One plane z = 5: the minimum moves x0 onto the plane and nowhere else.
  const auto m = quadric_minimum(Quadric::plane(0, 0, 1, -5, 2), {7, -4, 0});
  EXPECT_DOUBLE_EQ(m[0], 7.0);
  EXPECT_DOUBLE_EQ(m[1], -4.0);
  EXPECT_NEAR(m[2], 5.0, 5 * 1e-3);
}

TEST(QuadricMinimum, ZeroQuadricGivesTheStartingPoint) {
  const auto m = quadric_minimum(Quadric{}, {1, 2, 3});
  EXPECT_EQ(m, (std::array<double, 3>{1, 2, 3}));
}

}  // namespace
}  // namespace lodforge
