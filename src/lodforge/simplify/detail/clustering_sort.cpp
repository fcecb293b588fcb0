#include "lodforge/simplify/detail/clustering_sort.h"

#include <algorithm>
#include <array>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "lodforge/core/radix_sort.h"

namespace lodforge::detail::clustering {
namespace {

/// Keys per block of the split and (about) per group sorted on one thread:
/// below it a task costs more than it saves.
constexpr std::size_t kSortGrain = 16384;
/// The split's digit: the top 10 bits of the keys.
constexpr int kSplitBits = 10;
constexpr std::size_t kSplitBuckets = std::size_t(1) << kSplitBits;

std::size_t split_digit(std::uint64_t key) {
  return static_cast<std::size_t>(key >> (64 - kSplitBits));
}

/// Sorts `keys` by the whole comparison of sort_octree_order with `tmp` (as
/// long) as scratch: a radix sort of the top 32 bits, then each run of equal
/// top bits sorted by code, position and index.
void sort_group(std::span<std::uint64_t> keys, std::span<std::uint64_t> tmp,
                std::span<const std::uint64_t> code, std::span<const Vec3> positions) {
  const std::size_t n = keys.size();
  if (n > 1) radix_sort(keys, tmp, 32, 64);
  // The runs are those of equal sorted bits exactly: a code with bit 63 set
  // (an unused vertex's ~0) shares its top 32 bits with the cube's far corner.
  auto top = [](std::uint64_t key) { return static_cast<std::uint32_t>(key >> 32); };
  auto less = [&](std::uint64_t a, std::uint64_t b) {
    const auto va = static_cast<std::uint32_t>(a), vb = static_cast<std::uint32_t>(b);
    if (code[va] != code[vb]) return code[va] < code[vb];
    if (code[va] == kUnused) return va < vb;
    const Vec3& pa = positions[va];
    const Vec3& pb = positions[vb];
    if (pa.x != pb.x) return pa.x < pb.x;
    if (pa.y != pb.y) return pa.y < pb.y;
    if (pa.z != pb.z) return pa.z < pb.z;
    return va < vb;
  };
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    while (j < n && top(keys[j]) == top(keys[i])) ++j;
    if (j - i > 1) std::sort(keys.begin() + i, keys.begin() + j, less);
    i = j;
  }
}

/// Splits `keys` stably by their top kSplitBits into `out`; returns where
/// each bucket starts (kSplitBuckets + 1 entries). Each block of kSortGrain
/// keys counts its digits, then scatters to slots of its own in every bucket.
Buffer<std::size_t> split_by_top_bits(std::span<const std::uint64_t> keys,
                                      std::span<std::uint64_t> out) {
  const std::size_t n = keys.size();
  const std::size_t blocks = (n + kSortGrain - 1) / kSortGrain;
  auto block_range = [&](std::size_t b) {
    return std::pair{b * kSortGrain, std::min(n, (b + 1) * kSortGrain)};
  };
  Buffer<std::array<std::size_t, kSplitBuckets>> at(blocks);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1), [&](const auto& r) {
    for (std::size_t b = r.begin(); b < r.end(); ++b) {
      at[b].fill(0);
      const auto [i0, i1] = block_range(b);
      for (std::size_t i = i0; i < i1; ++i) ++at[b][split_digit(keys[i])];
    }
  });
  Buffer<std::size_t> start(kSplitBuckets + 1);
  std::size_t sum = 0;
  for (std::size_t d = 0; d < kSplitBuckets; ++d) {
    start[d] = sum;
    for (std::size_t b = 0; b < blocks; ++b) sum += std::exchange(at[b][d], sum);
  }
  start[kSplitBuckets] = n;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1), [&](const auto& r) {
    for (std::size_t b = r.begin(); b < r.end(); ++b) {
      const auto [i0, i1] = block_range(b);
      for (std::size_t i = i0; i < i1; ++i) out[at[b][split_digit(keys[i])]++] = keys[i];
    }
  });
  return start;
}

}  // namespace

void sort_octree_order(Buffer<std::uint64_t>& keys, std::span<const std::uint64_t> code,
                       std::span<const Vec3> positions) {
  const std::size_t n = keys.size();
  Buffer<std::uint64_t> tmp(n);
  if (n <= kSortGrain) return sort_group(keys, tmp, code, positions);
  const Buffer<std::size_t> start = split_by_top_bits(keys, tmp);
  keys.swap(tmp);
  // Groups of consecutive buckets of about kSortGrain keys: a run of equal
  // top 32 bits lies in one bucket, so in one group.
  Buffer<std::size_t> group{0};
  for (std::size_t d = 1; d < kSplitBuckets; ++d)
    if (start[d] - group.back() >= kSortGrain) group.push_back(start[d]);
  group.push_back(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, group.size() - 1, 1), [&](const auto& r) {
    for (std::size_t g = r.begin(); g < r.end(); ++g) {
      const std::size_t size = group[g + 1] - group[g];
      sort_group(std::span(keys).subspan(group[g], size), std::span(tmp).subspan(group[g], size),
                 code, positions);
    }
  });
}

}  // namespace lodforge::detail::clustering
