#include "lodforge/simplify/regions.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <memory>
#include <vector>

namespace lodforge {
namespace {

TEST(Regions, PartCountIsAPowerOfTwoBetweenTwoAndTheMaximum) {
  EXPECT_EQ(regions::part_count(0), 2);
  EXPECT_EQ(regions::part_count(regions::kTrianglesPerPart), 2);
  EXPECT_EQ(regions::part_count(4 * regions::kTrianglesPerPart), 4);
  EXPECT_EQ(regions::part_count(1000 * regions::kTrianglesPerPart), regions::kMaxParts);
}

TEST(Regions, GoalIsTwiceTheTargetButLeavesATenthOfTheWork) {
  EXPECT_EQ(regions::goal(100, 100'000), 200u);
  // Halving: twice the target is everything, a tenth of the collapses stays.
  EXPECT_EQ(regions::goal(50'000, 100'000), 55'000u);
  EXPECT_TRUE(regions::worthwhile(10'000, 100'000));
  EXPECT_FALSE(regions::worthwhile(90'000, 100'000));                 // keeps too much
  EXPECT_FALSE(regions::worthwhile(10, regions::kMinTriangles - 1));  // too small
}

TEST(Regions, KdPartitionSplitsSeparatedClustersApartAndEvenly) {
  // Four clusters of 100 centroids at the corners of a square; triangle 400
  // is unused.
  std::vector<float> centre;
  std::vector<std::uint8_t> use;
  const std::array<std::array<float, 2>, 4> corners{{{0, 0}, {10, 0}, {0, 10}, {10, 10}}};
  for (const auto& c : corners)
    for (int i = 0; i < 100; ++i) {
      centre.insert(centre.end(), {c[0] + 0.01f * i, c[1] + 0.005f * i, 0});
      use.push_back(1);
    }
  centre.insert(centre.end(), {5, 5, 0});
  use.push_back(0);
  const std::vector<std::uint8_t> region = regions::kd_partition(centre, use, 4);
  ASSERT_EQ(region.size(), use.size());
  EXPECT_EQ(region[400], 0);
  std::array<int, 4> count{};
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 100; ++i) {
      ASSERT_LT(region[100 * k + i], 4);
      EXPECT_EQ(region[100 * k + i], region[100 * k]) << "cluster " << k << " is cut";
      ++count[region[100 * k + i]];
    }
  for (int r = 0; r < 4; ++r) EXPECT_EQ(count[r], 100) << "region " << r;
}

TEST(Regions, NextLimitGrowsFasterFarFromTheGoalAndSaturates) {
  const std::uint32_t one = 0x3f800000u;  // 1.0f
  const std::uint32_t far = regions::next_limit(one, 1000, 10, 0);
  const std::uint32_t mid = regions::next_limit(one, 30, 10, 0);
  const std::uint32_t near = regions::next_limit(one, 15, 10, 0);
  EXPECT_EQ(far - one, 4u << 23);   // x16
  EXPECT_EQ(mid - one, 2u << 23);   // x4
  EXPECT_EQ(near - one, 1u << 23);  // x2
  EXPECT_EQ(regions::next_limit(0xffffff00u, 1000, 10, 0), 0xffffffffu);
}

struct Lane {
  std::size_t inner = 0;
  bool done = false;
  std::vector<std::uint32_t> limits;
};

TEST(Regions, RunRoundsStopsAtTheGoalAndPassesGrowingLimits) {
  std::vector<std::unique_ptr<Lane>> lanes;
  for (int i = 0; i < 3; ++i) lanes.push_back(std::make_unique<Lane>(Lane{.inner = 100}));
  // Each step removes 10 inner triangles; the goal of 150 of 300 is reached
  // after 5 rounds.
  regions::run_rounds(lanes, 150, 0x3f800000u, 0, [](Lane& lane, std::uint32_t limit) {
    lane.limits.push_back(limit);
    lane.inner -= 10;
    return false;
  });
  for (const auto& lane : lanes) {
    EXPECT_EQ(lane->inner, 50u);
    EXPECT_TRUE(std::is_sorted(lane->limits.begin(), lane->limits.end()));
    EXPECT_EQ(lane->limits, lanes[0]->limits);
  }
}

TEST(Regions, RunRoundsSkipsDoneLanesAndEndsWhenAllAreDone) {
  std::vector<std::unique_ptr<Lane>> lanes;
  lanes.push_back(std::make_unique<Lane>(Lane{.inner = 100}));
  lanes.push_back(std::make_unique<Lane>(Lane{.inner = 100, .done = true}));
  int steps = 0;
  regions::run_rounds(lanes, 0, 0x3f800000u, 0, [&](Lane& lane, std::uint32_t) {
    ++steps;
    return ++lane.inner > 102;  // done after three rounds
  });
  EXPECT_EQ(steps, 3);
  EXPECT_EQ(lanes[1]->inner, 100u);
}

}  // namespace
}  // namespace lodforge
