#include "lodforge/core/morton.h"

#include <gtest/gtest.h>

#include <vector>

namespace lodforge {
namespace {

// Bit by bit against the definition.
std::uint64_t slow_code(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  std::uint64_t c = 0;
  for (int i = 0; i < 21; ++i) {
    c |= std::uint64_t{x >> i & 1} << (3 * i);
    c |= std::uint64_t{y >> i & 1} << (3 * i + 1);
    c |= std::uint64_t{z >> i & 1} << (3 * i + 2);
  }
  return c;
}

TEST(Morton, InterleavesTwentyOneBitsOfEachAxis) {
  static_assert(morton_code(1, 0, 0) == 1 && morton_code(0, 1, 0) == 2 &&
                morton_code(0, 0, 1) == 4);
  const std::uint32_t values[] = {0, 1, 2, 5, 0x155555, 0x0aaaaa, 0x1fffff, 123456, 0x7fffffff};
  for (std::uint32_t x : values)
    for (std::uint32_t y : values)
      for (std::uint32_t z : values)
        EXPECT_EQ(morton_code(x, y, z), slow_code(x & 0x1fffff, y & 0x1fffff, z & 0x1fffff));
  EXPECT_EQ(morton_code(0x1fffff, 0x1fffff, 0x1fffff), (std::uint64_t{1} << 63) - 1);
}

// Points sorted octant by octant over their box; equal points keep their
// index order; the index is in the low 32 bits.
TEST(Morton, SortedKeysOrderPointsCellByCell) {
  const std::vector<Vec3> points = {{1, 1, 1}, {0, 0, 0}, {1, 0, 0}, {0, 0, 0}, {0, 1, 0}};
  const std::vector<std::uint64_t> keys = morton_sorted_keys(points);
  std::vector<std::uint32_t> order;
  for (std::uint64_t k : keys) order.push_back(std::uint32_t(k));
  EXPECT_EQ(order, (std::vector<std::uint32_t>{1, 3, 2, 4, 0}));
  EXPECT_EQ(keys.back() >> 32, morton_code(1023, 1023, 1023));
  EXPECT_TRUE(morton_sorted_keys({}).empty());
}

}  // namespace
}  // namespace lodforge
