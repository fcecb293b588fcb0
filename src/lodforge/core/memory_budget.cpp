#include "lodforge/core/memory_budget.h"

#include <fmt/format.h>

#include "lodforge/core/error.h"

namespace lodforge {

void check_memory_budget(double bytes, std::uint64_t budget, std::string_view what,
                         std::string_view hint) {
  if (budget == 0 || bytes <= static_cast<double>(budget)) return;
  constexpr double kGiB = double(std::uint64_t{1} << 30);
  throw DataError(fmt::format(
      "{} needs about {:.3g} GiB, more than the memory budget of {:.3g} "
      "GiB{}{}",
      what, bytes / kGiB, static_cast<double>(budget) / kGiB, hint.empty() ? "" : "; ", hint));
}

}  // namespace lodforge
