#pragma once
/// Connected regions of a sign lattice, and the clean-up of a lattice whose
/// signs come from range scans (detail of the marching-cube octree build).
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace lodforge::detail {

struct SignCleanup {
  std::size_t filled_voids = 0;   ///< outside regions enclosed by the inside, made inside
  std::size_t filled_points = 0;  ///< their lattice points
  std::size_t dropped_parts = 0;  ///< small inside regions made outside
  std::size_t dropped_points = 0;
};

/// Cleans the signs of a lattice of dim[0] x dim[1] x dim[2] points (x
/// fastest; `state[i] & inside_bit` = point i is inside; other bits are kept)
/// the way a scanned solid needs them. Regions are 6-connected.
///   * Every outside region that does not reach the lattice's border is
///     filled (made inside): a range scanner sees only an object's outer
///     surface, so such a void is sign noise (typically between overlapping
///     scans out of register) and its surface would lie hidden inside.
///   * Every inside region with fewer than `min_part` points, or fewer than
///     `min_part_fraction` times the largest region's, is dropped (made
///     outside): a bubble around stray points, not a part of the object.
/// Work and memory linear in the lattice.
SignCleanup clean_scan_signs(std::vector<std::uint8_t>& state,
                             const std::array<std::int64_t, 3>& dim, std::uint8_t inside_bit,
                             std::size_t min_part, double min_part_fraction);

}  // namespace lodforge::detail
