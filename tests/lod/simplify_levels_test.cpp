#include "lodforge/lod/simplify_levels.h"

#include <gtest/gtest.h>

#include <random>

#include "lodforge/lod/measure_deviation.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

TriangleMesh bumpy_sphere() {
  return test::make_bumpy_sphere(11);
}

TEST(SimplifyLevels, EveryLevelMeasuredInFullWithoutAKeepRule) {
  const TriangleMesh mesh = bumpy_sphere();
  const auto levels = simplify_levels(mesh, {});
  ASSERT_GE(levels.size(), 5u);
  DeviationMeter meter(mesh, {.samples = measure_samples_for(mesh.triangle_count(), 0)});
  for (const auto& l : levels) {
    EXPECT_TRUE(l.measured_in_full);
    EXPECT_EQ(l.error, kErrorMargin * meter.hausdorff(l.level.mesh, l.level.face_map));
  }
  for (std::size_t i = 1; i < levels.size(); ++i)
    EXPECT_LT(levels[i].level.mesh.triangle_count(), levels[i - 1].level.mesh.triangle_count());
}

// With a keep rule, the levels it keeps in the end are measured in full (the
// same figure as without the rule), the others estimated (calibrated against
// the nearest ones measured in full), and the rule is asked again after each
// round of full measurements.
TEST(SimplifyLevels, OnlyTheKeptLevelsAreMeasuredInFull) {
  const TriangleMesh mesh = bumpy_sphere();
  const auto all = simplify_levels(mesh, {});
  LevelChainOptions options;
  int asked = 0;
  // Keeps the levels whose error (estimated or full) is the largest of every
  // third level: a choice that depends on the figures, as the spacing does.
  options.keep = [&](std::span<const MeasuredLevel> levels) {
    ++asked;
    std::vector<std::size_t> kept;
    for (std::size_t i = 0; i + 2 < levels.size(); i += 3) {
      std::size_t best = i;
      for (std::size_t k = i; k < i + 3; ++k)
        if (levels[k].error > levels[best].error) best = k;
      kept.push_back(best);
    }
    return kept;
  };
  const auto levels = simplify_levels(mesh, options);
  ASSERT_EQ(levels.size(), all.size());
  EXPECT_EQ(asked, 1);  // one choice, on the estimates
  const auto kept = options.keep(levels);
  ASSERT_FALSE(kept.empty());
  std::size_t full = 0;
  for (std::size_t i = 0; i < levels.size(); ++i) {
    EXPECT_EQ(levels[i].level.mesh.triangles, all[i].level.mesh.triangles) << i;
    if (levels[i].measured_in_full) {
      ++full;
      EXPECT_EQ(levels[i].error, all[i].error) << i;
    } else {
      EXPECT_GT(levels[i].error, 0.0) << i;  // estimated
      // One direction, thinly: of the size of the full measurement.
      EXPECT_LT(levels[i].error, 1.25 * all[i].error) << i;
      EXPECT_GT(levels[i].error, 0.25 * all[i].error) << i;
    }
  }
  for (std::size_t i : kept) EXPECT_TRUE(levels[i].measured_in_full) << i;
  EXPECT_LT(full, levels.size());
  // The same answer again (deterministic).
  const auto again = simplify_levels(mesh, options);
  for (std::size_t i = 0; i < levels.size(); ++i) {
    EXPECT_EQ(again[i].error, levels[i].error) << i;
    EXPECT_EQ(again[i].measured_in_full, levels[i].measured_in_full) << i;
  }
}

}  // namespace
}  // namespace lodforge
