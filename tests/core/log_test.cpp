// The diagnostics log: levels, categories by name, the sink, merging.
#include "lodforge/core/log.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace lodforge {
namespace {

TEST(Log, CategoriesRoundTripThroughTheirNames) {
  for (int i = 0; i < 10; ++i) {
    const auto c = static_cast<LogCategory>(i);
    LogCategory back = LogCategory::kGeneral;
    ASSERT_TRUE(parse_category(to_string(c), back)) << to_string(c);
    EXPECT_EQ(back, c);
  }
  EXPECT_EQ(to_string(LogCategory::kTriangulator), "triangulator");
  LogCategory untouched = LogCategory::kFace;
  EXPECT_FALSE(parse_category("faces", untouched));
  EXPECT_EQ(untouched, LogCategory::kFace);
  EXPECT_EQ(to_string(LogLevel::kWarning), "warning");
  EXPECT_EQ(to_string(LogLevel::kInternal), "internal");
}

TEST(Log, EntriesReachTheSinkInOrderAndAreCountedByLevel) {
  Log log;
  std::vector<std::string> seen;
  log.sink = [&](const Diagnostic& d) {
    seen.push_back(std::string(to_string(d.level)) + " " + d.text);
  };
  log.warn(LogCategory::kParse, "a");
  log.info(LogCategory::kGeneral, "b");
  log.add(LogLevel::kError, LogCategory::kCoord, "c");
  log.warn(LogCategory::kFace, "d");
  EXPECT_EQ(seen, (std::vector<std::string>{"warning a", "message b", "error c", "warning d"}));
  EXPECT_EQ(log.count(LogLevel::kWarning), 2u);
  EXPECT_EQ(log.count(LogLevel::kError), 1u);
  EXPECT_EQ(log.count(LogLevel::kInternal), 0u);
  // Merging appends the other log's entries and passes them to this sink.
  Log other;
  other.warn(LogCategory::kMaterial, "e");
  log.merge(other);
  ASSERT_EQ(log.entries().size(), 5u);
  EXPECT_EQ(log.entries().back().category, LogCategory::kMaterial);
  EXPECT_EQ(seen.back(), "warning e");
}

}  // namespace
}  // namespace lodforge
