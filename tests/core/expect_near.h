#pragma once
// A point or vector equal to another within a tolerance, coordinate by
// coordinate (GoogleTest reports the coordinate that differs).
#include <gtest/gtest.h>

#include "lodforge/core/math.h"

namespace lodforge::test {

inline void expect_near(const Vec3& a, const Vec3& b, float tolerance = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

}  // namespace lodforge::test
