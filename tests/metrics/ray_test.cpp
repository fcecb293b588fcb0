#include "lodforge/metrics/ray.h"

#include <gtest/gtest.h>

namespace lodforge {
namespace {

const Vec3 kA{0, 0, 0}, kB{1, 0, 0}, kC{0, 1, 0};

// Through the triangle's interior from either side; beside it, behind the
// origin, parallel to its plane and at a collapsed triangle: no hit.
TEST(Ray, HitsTheSolidTriangleFromEitherSide) {
  EXPECT_DOUBLE_EQ(Ray({0.25f, 0.25f, 2}, {0, 0, -1}).hit(kA, kB, kC), 2);
  EXPECT_DOUBLE_EQ(Ray({0.25f, 0.25f, -3}, {0, 0, 1}).hit(kA, kB, kC), 3);
  EXPECT_EQ(Ray({0.75f, 0.75f, 2}, {0, 0, -1}).hit(kA, kB, kC), -1);  // beside the hypotenuse
  EXPECT_EQ(Ray({0.25f, 0.25f, 2}, {0, 0, 1}).hit(kA, kB, kC), -1);   // pointing away
  EXPECT_EQ(Ray({-1, 0.25f, 0}, {1, 0, 0}).hit(kA, kB, kC), -1);      // in its plane
  EXPECT_EQ(Ray({0.5f, 0, 2}, {0, 0, -1}).hit(kA, kB, kB), -1);       // collapsed
  // An origin on the triangle: t = 0.
  EXPECT_DOUBLE_EQ(Ray({0.25f, 0.25f, 0}, {0, 0, 1}).hit(kA, kB, kC), 0);
  // On an edge and at a corner: hit (the solid triangle includes them).
  EXPECT_DOUBLE_EQ(Ray({0.5f, 0, 1}, {0, 0, -1}).hit(kA, kB, kC), 1);
  EXPECT_DOUBLE_EQ(Ray({0, 0, 1}, {0, 0, -1}).hit(kA, kB, kC), 1);
  // Oblique: the distance is along the unit direction.
  const float s = std::sqrt(0.5f);
  EXPECT_NEAR(Ray({0.25f, -0.75f, 1}, {0, s, -s}).hit(kA, kB, kC), std::sqrt(2.0), 1e-6);
}

TEST(Ray, EntersBoxes) {
  const Vec3 lo{0, 0, 0}, hi{1, 1, 1};
  EXPECT_FLOAT_EQ(Ray({-2, 0.5f, 0.5f}, {1, 0, 0}).enter(lo, hi, 10), 2);
  EXPECT_FLOAT_EQ(Ray({0.5f, 0.5f, 0.5f}, {1, 0, 0}).enter(lo, hi, 10), 0);  // inside
  EXPECT_EQ(Ray({-2, 0.5f, 0.5f}, {1, 0, 0}).enter(lo, hi, 1.5f), -1);       // stops short
  EXPECT_EQ(Ray({-2, 0.5f, 0.5f}, {-1, 0, 0}).enter(lo, hi, 10), -1);        // away
  EXPECT_EQ(Ray({-2, 1.5f, 0.5f}, {1, 0, 0}).enter(lo, hi, 10), -1);         // beside
  // Along a face (flat components tested by position, no 0 x inf).
  EXPECT_FLOAT_EQ(Ray({-2, 1, 0}, {1, 0, 0}).enter(lo, hi, 10), 2);
  const float s = std::sqrt(0.5f);
  EXPECT_NEAR(Ray({-1, -1, 0.5f}, {s, s, 0}).enter(lo, hi, 10), std::sqrt(2.0f), 1e-6);
}

}  // namespace
}  // namespace lodforge
