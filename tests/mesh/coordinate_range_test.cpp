// The supported coordinate range: huge, tiny and non-finite models are refused
// with the file's name and the range; models inside it pass.
#include "lodforge/mesh/coordinate_range.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lodforge/core/error.h"

namespace lodforge {
namespace {

using ::testing::HasSubstr;

// A triangle of side `s` at `offset` from the origin.
TriangleMesh triangle(float s, float offset = 0) {
  TriangleMesh m;
  m.positions = {
      {offset, offset, offset}, {offset + s, offset, offset}, {offset, offset + s, offset}};
  m.triangles = {{0, 1, 2}};
  return m;
}

std::string message_of(const TriangleMesh& m) {
  try {
    check_coordinate_range(m, "m.obj");
  } catch (const DataError& e) {
    return e.what();
  }
  return "";
}

TEST(CoordinateRange, ModelsInsideTheRangePass) {
  EXPECT_EQ(message_of(triangle(1)), "");
  EXPECT_EQ(message_of(triangle(1e-6f)), "");
  EXPECT_EQ(message_of(triangle(1e8f, -5e8f)), "");
  EXPECT_EQ(message_of(TriangleMesh{}), "");
}

TEST(CoordinateRange, AllAtOnePointIsLeftToTheAlgorithms) {
  EXPECT_EQ(message_of(triangle(0, 3)), "");
}

TEST(CoordinateRange, HugeCoordinatesAreRefused) {
  const std::string m = message_of(triangle(1, 1e38f));
  EXPECT_THAT(m, HasSubstr("m.obj: a coordinate of magnitude 1e+38"));
  EXPECT_THAT(m, HasSubstr("at most 1e+09"));
}

TEST(CoordinateRange, TinyModelsAreRefused) {
  EXPECT_THAT(message_of(triangle(1e-38f)), HasSubstr("m.obj: the model is only 1e-38 across"));
}

TEST(CoordinateRange, NonFinitePositionsAreRefused) {
  TriangleMesh m = triangle(1);
  m.positions[1].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THAT(message_of(m), HasSubstr("m.obj: a vertex position is not finite"));
}

}  // namespace
}  // namespace lodforge
