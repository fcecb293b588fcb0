#pragma once
/// A stable least-significant-digit radix sort of 64-bit keys by a range of
/// their bits.
#include <cstdint>
#include <span>

namespace lodforge {

/// Sorts `keys` stably by bits [low_bit, high_bit) (0 <= low_bit < high_bit
/// <= 64) taken as an unsigned number; the other bits travel with the key
/// and do not take part. `scratch` must be at least as long as `keys`; its
/// contents are overwritten. Passes of at most 11 bits, all counted in one
/// read of the keys; a pass in which every key has the same digit is
/// skipped. O(n) time per pass, on the calling thread; deterministic.
void radix_sort(std::span<std::uint64_t> keys, std::span<std::uint64_t> scratch, int low_bit,
                int high_bit);

}  // namespace lodforge
