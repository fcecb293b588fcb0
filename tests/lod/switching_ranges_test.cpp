// The switching-distance formula and the behaviour of the original's Table B.5.
#include "lodforge/lod/switching_ranges.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lodforge {
namespace {

TEST(SwitchingRanges, FormulaOfTheSpec) {
  // d = k eps / (2 tan(alpha/2) p) + r
  RangeOptions o{.error_range = 0.02f, .camera_angle = 0.785398f};
  double d = switch_distance(0.01, 2.0, 0.5, o);
  EXPECT_NEAR(d, 2.0 * 0.01 / (2 * std::tan(0.785398 / 2) * 0.02) + 0.5, 1e-6);
}

TEST(SwitchingRanges, LowerErrorRangeGivesLargerDistances) {
  // Table B.5 (cow): 0.1 % -> 33.9 m, 2 % -> 2.83 m, 10 % -> 1.52 m for the first switch.
  std::vector<double> errors = {0.001, 0.002, 0.004, 0.008};
  auto fine = switching_ranges(errors, 1, 1, {.error_range = 0.001f});
  auto normal = switching_ranges(errors, 1, 1, {.error_range = 0.02f});
  auto coarse = switching_ranges(errors, 1, 1, {.error_range = 0.10f});
  for (std::size_t i = 0; i < errors.size(); ++i) {
    EXPECT_GT(fine[i], normal[i]);
    EXPECT_GT(normal[i], coarse[i]);
  }
  // Each level's distance grows with its error; doubling the error roughly
  // doubles the distance beyond the radius.
  for (std::size_t i = 1; i < errors.size(); ++i) {
    EXPECT_GT(normal[i], normal[i - 1]);
    EXPECT_NEAR((normal[i] - 1) / (normal[i - 1] - 1), 2.0, 1e-4);
  }
}

TEST(SwitchingRanges, NonMonotoneErrorsStillGiveIncreasingRanges) {
  std::vector<double> errors = {0.02, 0.01, 0.01, 0.03};
  auto r = switching_ranges(errors, 1, 0, {});
  ASSERT_EQ(r.size(), 4u);
  for (std::size_t i = 1; i < r.size(); ++i) EXPECT_LT(r[i - 1], r[i]);
  EXPECT_FLOAT_EQ(r[0], float(switch_distance(0.02, 1, 0, {})));
}

TEST(SwitchingRanges, ScaleOfTheTransformScalesTheDistance) {
  double a = switch_distance(0.1, 1, 0, {});
  double b = switch_distance(0.1, 3, 0, {});
  EXPECT_NEAR(b, 3 * a, 1e-9);
}

// Candidates with tiny errors crowd just beyond the radius; spacing keeps one
// level per 1.25x of distance, the coarsest each distance allows, and none the
// viewer would see over a shorter interval before the object vanishes.
TEST(SpaceLevels, KeepsTheCoarsestLevelPerSpacedDistance) {
  const double r = 1;
  std::vector<double> errors;
  for (int i = 1; i <= 40; ++i) errors.push_back(1e-4 * std::pow(1.3, i));  // up to ~3.6 r
  SpacedLevels s = space_levels({.errors = errors}, r, {}, {.spacing = 1.25});
  ASSERT_GE(s.levels.size(), 3u);
  EXPECT_TRUE(s.vanished);
  const double vanish = switch_distance(vanishing_error(r), 1, r, {});
  double previous = 0;
  for (std::size_t i = 0; i < s.levels.size(); ++i) {
    const SpacedLevel& l = s.levels[i];
    const double d = switch_distance(l.switch_error, 1, r, {});
    EXPECT_GE(l.switch_error, errors[l.candidate]);  // never nearer than its error allows
    if (i > 0) {
      EXPECT_GE(d, 1.25 * previous * (1 - 1e-9)) << i;
      EXPECT_GT(l.candidate, s.levels[i - 1].candidate);
    }
    // The next candidate would not be allowed yet at this distance.
    if (l.candidate + 1 < errors.size())
      EXPECT_GT(switch_distance(errors[l.candidate + 1], 1, r, {}), d * (1 + 1e-12)) << i;
    previous = d;
  }
  EXPECT_LE(1.25 * previous, vanish);
  // Without spacing every candidate below the vanishing distance is kept.
  SpacedLevels all = space_levels({.errors = errors}, r, {}, {.spacing = 1.0});
  EXPECT_GT(all.levels.size(), s.levels.size());
  for (std::size_t i = 0; i < all.levels.size(); ++i) EXPECT_EQ(all.levels[i].candidate, i);
}

TEST(SpaceLevels, ErrorFreeCandidatesCollapseToTheCoarsest) {
  // A flat patch simplified without error: the coarsest candidate is shown
  // from the radius on, the finer ones never.
  std::vector<double> errors = {0, 0, 0, 0};
  SpacedLevels s = space_levels({.errors = errors}, 2.0, {});
  ASSERT_EQ(s.levels.size(), 1u);
  EXPECT_EQ(s.levels[0].candidate, 3u);
  EXPECT_DOUBLE_EQ(s.levels[0].switch_error, 0);
  EXPECT_FALSE(s.vanished);
}

TEST(SpaceLevels, EachLevelHasAtMostTheRatioOfTheOneBefore) {
  // Candidates 20 % apart in size, errors growing as for a smooth surface.
  std::vector<double> errors;
  std::vector<std::size_t> triangles;
  for (int i = 1; i <= 25; ++i) {
    triangles.push_back(std::size_t(100000 * std::pow(0.8, i)));
    errors.push_back(1e-3 / std::sqrt(double(triangles.back()) / 100000));
  }
  const LevelCandidates c{.errors = errors, .triangles = triangles, .level0_triangles = 100000};
  for (double ratio : {0.5, 0.25}) {
    SpacedLevels s = space_levels(c, 1.0, {}, {.max_ratio = ratio});
    ASSERT_GE(s.levels.size(), 2u) << ratio;
    std::size_t before = 100000, total = 0;
    for (const SpacedLevel& l : s.levels) {
      EXPECT_LE(double(triangles[l.candidate]), ratio * double(before)) << ratio;
      before = triangles[l.candidate];
      total += before;
    }
    EXPECT_LE(double(total), ratio / (1 - ratio) * 100000) << ratio;
  }
  // Without the rule a level 80 % of the one before it is worth keeping here.
  SpacedLevels free = space_levels(c, 1.0, {}, {.max_ratio = 1});
  bool close = false;
  std::size_t before = 100000;
  for (const SpacedLevel& l : free.levels) {
    close = close || triangles[l.candidate] > before / 2;
    before = triangles[l.candidate];
  }
  EXPECT_TRUE(close);
}

TEST(SpaceLevels, NothingPastTheVanishingError) {
  std::vector<double> errors = {3.0, 4.0};  // radius 1: beyond 2 r
  SpacedLevels s = space_levels({.errors = errors}, 1.0, {});
  EXPECT_TRUE(s.levels.empty());
  EXPECT_TRUE(s.vanished);
}

}  // namespace
}  // namespace lodforge
