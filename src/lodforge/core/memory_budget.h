#pragma once
/// A bound on the memory one step may allocate, checked from an estimate
/// before the allocation, so that a huge count from a file or an option is
/// refused with a message instead of exhausting the machine.
#include <cstdint>
#include <string_view>

namespace lodforge {

/// The default budget of one step: 8 GiB (a third of the machines the
/// toolkit is built for).
inline constexpr std::uint64_t kDefaultMemoryBudget = std::uint64_t{8} << 30;

/// Throws DataError "`what` needs about X GiB, more than the memory budget of
/// Y GiB; `hint`" when `bytes` (an estimate; may be huge or infinite) exceeds
/// `budget`. A budget of 0 means no limit.
void check_memory_budget(double bytes, std::uint64_t budget, std::string_view what,
                         std::string_view hint);

}  // namespace lodforge
