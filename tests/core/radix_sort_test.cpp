#include "lodforge/core/radix_sort.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace lodforge {
namespace {

std::vector<std::uint64_t> random_keys(std::size_t n, std::uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::uint64_t> keys(n);
  for (auto& k : keys) k = rng();
  return keys;
}

TEST(RadixSort, AllBitsGiveTheSortedOrder) {
  auto keys = random_keys(10000, 1);
  std::vector<std::uint64_t> scratch(keys.size());
  auto expected = keys;
  std::sort(expected.begin(), expected.end());
  radix_sort(keys, scratch, 0, 64);
  EXPECT_EQ(keys, expected);
}

TEST(RadixSort, SortsByTheBitRangeAndKeepsEqualDigitsInTheirOrder) {
  // Bits [32, 64) are the key, the low 32 bits each item's index: stable
  // means equal keys keep their indices increasing.
  std::mt19937 rng(2);
  std::vector<std::uint64_t> keys(5000);
  for (std::uint32_t i = 0; i < keys.size(); ++i)
    keys[i] = std::uint64_t(rng() % 300) << 32 | i;  // many equal keys
  auto expected = keys;
  std::stable_sort(expected.begin(), expected.end(),
                   [](std::uint64_t a, std::uint64_t b) { return (a >> 32) < (b >> 32); });
  std::vector<std::uint64_t> scratch(keys.size());
  radix_sort(keys, scratch, 32, 64);
  EXPECT_EQ(keys, expected);
}

TEST(RadixSort, OddRangesAndSinglePasses) {
  for (auto [lo, hi] : {std::pair{0, 1}, std::pair{3, 14}, std::pair{0, 63}, std::pair{20, 41}}) {
    auto keys = random_keys(3000, 3 + lo + hi);
    const std::uint64_t mask =
        hi - lo == 64 ? ~std::uint64_t(0) : ((std::uint64_t(1) << (hi - lo)) - 1) << lo;
    auto expected = keys;
    std::stable_sort(expected.begin(), expected.end(),
                     [&](std::uint64_t a, std::uint64_t b) { return (a & mask) < (b & mask); });
    std::vector<std::uint64_t> scratch(keys.size() + 7);
    radix_sort(keys, scratch, lo, hi);
    EXPECT_EQ(keys, expected) << lo << ".." << hi;
  }
}

TEST(RadixSort, EmptyOneAndAllEqual) {
  std::vector<std::uint64_t> none, scratch(4);
  radix_sort(none, scratch, 0, 64);
  EXPECT_TRUE(none.empty());
  std::vector<std::uint64_t> one{42};
  radix_sort(one, scratch, 0, 64);
  EXPECT_EQ(one, std::vector<std::uint64_t>{42});
  std::vector<std::uint64_t> same{7, 7, 7, 7};
  radix_sort(same, scratch, 0, 64);
  EXPECT_EQ(same, (std::vector<std::uint64_t>{7, 7, 7, 7}));
}

}  // namespace
}  // namespace lodforge
