#include "lodforge/core/radix_sort.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <utility>
#include <vector>

namespace lodforge {

void radix_sort(std::span<std::uint64_t> keys, std::span<std::uint64_t> scratch, int low_bit,
                int high_bit) {
  assert(0 <= low_bit && low_bit < high_bit && high_bit <= 64);
  assert(scratch.size() >= keys.size());
  constexpr int kMaxBits = 11;
  constexpr std::size_t kBuckets = std::size_t(1) << kMaxBits;
  // The bits split into passes as evenly as possible (32 bits: 11, 11, 10).
  const int bits = high_bit - low_bit;
  const int passes = (bits + kMaxBits - 1) / kMaxBits;
  std::array<int, 6> shift{}, width{};
  for (int p = 0, at = low_bit; p < passes; ++p) {
    width[p] = (bits - (at - low_bit) + (passes - p) - 1) / (passes - p);
    shift[p] = at;
    at += width[p];
  }
  auto digit = [&](std::uint64_t key, int p) {
    return static_cast<std::size_t>((key >> shift[p]) & ((std::uint64_t(1) << width[p]) - 1));
  };
  const std::size_t n = keys.size();
  std::vector<std::array<std::size_t, kBuckets>> count(passes);
  for (auto& c : count) c.fill(0);
  for (std::uint64_t key : keys)
    for (int p = 0; p < passes; ++p) ++count[p][digit(key, p)];
  std::uint64_t* from = keys.data();
  std::uint64_t* to = scratch.data();
  for (int p = 0; p < passes; ++p) {
    auto& c = count[p];
    if (std::find(c.begin(), c.end(), n) != c.end()) continue;  // one digit: nothing moves
    std::size_t sum = 0;
    for (auto& k : c) sum += std::exchange(k, sum);
    for (std::size_t i = 0; i < n; ++i) to[c[digit(from[i], p)]++] = from[i];
    std::swap(from, to);
  }
  if (from != keys.data()) std::copy_n(from, n, keys.data());
}

}  // namespace lodforge
