#pragma once
/// Morton (Z-order) codes: the bits of three 21-bit integers interleaved, so
/// that sorting by code groups points octree cell by octree cell.
#include <cstdint>
#include <span>
#include <vector>

#include "lodforge/core/math.h"

namespace lodforge {

/// The low 21 bits of v spread out: bit i moves to bit 3i.
constexpr std::uint64_t morton_spread(std::uint32_t v) {
  std::uint64_t x = v & 0x1fffffu;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

/// x in bits 0, 3, 6, …, y in bits 1, 4, …, z in bits 2, 5, … (21 bits each).
constexpr std::uint64_t morton_code(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  return morton_spread(x) | morton_spread(y) << 1 | morton_spread(z) << 2;
}

/// Points in Morton order: per point, its code (10 bits per axis over the
/// points' bounding box) above its index, sorted by the code; points of one
/// code stay in index order. O(n), deterministic.
std::vector<std::uint64_t> morton_sorted_keys(std::span<const Vec3> points);

}  // namespace lodforge
