// The memory budget refuses estimates above it, with the estimate in GiB.
#include "lodforge/core/memory_budget.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "lodforge/core/error.h"

namespace lodforge {
namespace {

using ::testing::HasSubstr;

std::string message_of(double bytes, std::uint64_t budget) {
  try {
    check_memory_budget(bytes, budget, "sampling", "use fewer");
  } catch (const DataError& e) {
    return e.what();
  }
  return "";
}

TEST(MemoryBudget, WithinTheBudgetPasses) {
  EXPECT_EQ(message_of(1e9, kDefaultMemoryBudget), "");
  EXPECT_EQ(message_of(double(kDefaultMemoryBudget), kDefaultMemoryBudget), "");
}

TEST(MemoryBudget, AboveTheBudgetNamesTheEstimate) {
  EXPECT_EQ(message_of(16.0 * (1 << 30), kDefaultMemoryBudget),
            "sampling needs about 16 GiB, more than the memory budget of 8 GiB; use fewer");
}

TEST(MemoryBudget, HugeAndInfiniteEstimatesAreRefused) {
  EXPECT_THAT(message_of(1e30, kDefaultMemoryBudget), HasSubstr("about 9.31e+20 GiB"));
  EXPECT_THAT(message_of(std::numeric_limits<double>::infinity(), 1), HasSubstr("about inf GiB"));
}

TEST(MemoryBudget, ZeroMeansNoLimit) {
  EXPECT_EQ(message_of(1e30, 0), "");
}

}  // namespace
}  // namespace lodforge
