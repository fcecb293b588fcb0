#include "lodforge/lod/choose_levels.h"

#include <gtest/gtest.h>

#include <limits>

#include "lodforge/core/error.h"

#include "lodforge/lod/measure_deviation.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

double radius_of(const TriangleMesh& mesh) {
  double r = 0;
  for (const Vec3& p : mesh.positions) r = std::max(r, double(length(p)));
  return r;
}

// Automatic mode: every chosen level is measured in full, switches no
// earlier than its error allows, keeps at most the level ratio of the
// triangles before it, and the levels switch at distances spaced by at least
// the spacing factor.
TEST(ChooseLevels, AutomaticLevelsAreSpacedMeasuredAndSmaller) {
  const TriangleMesh mesh = test::make_bumpy_sphere(11);
  const double r = radius_of(mesh);
  const ChooseLevelsOptions options;
  const ChosenLevels chosen = choose_levels(mesh, r, options);
  ASSERT_GE(chosen.levels.size(), 2u);
  EXPECT_EQ(chosen.method, "qem");
  EXPECT_FALSE(chosen.stop_reason.empty());
  std::size_t before = mesh.triangle_count();
  double previous_distance = 0;
  DeviationMeter meter(mesh, {.samples = measure_samples_for(mesh.triangle_count(), 0)});
  for (const ChosenLevel& l : chosen.levels) {
    EXPECT_TRUE(l.measured.measured_in_full);
    // The level's full measurement started from its estimate, so its local
    // searches started at other samples: equal to a measurement from scratch
    // up to what those searches find.
    const double error =
        kErrorMargin * meter.hausdorff(l.measured.level.mesh, l.measured.level.face_map);
    EXPECT_NEAR(l.measured.error, error, 1e-3 * error);
    EXPECT_GE(l.switch_error, l.measured.error);
    const std::size_t n = l.measured.level.mesh.triangle_count();
    EXPECT_LE(double(n), options.spacing.max_ratio * double(before));
    before = n;
    const double d = switch_distance(l.switch_error, 1.0, r, options.range);
    if (previous_distance > 0) EXPECT_GE(d, options.spacing.spacing * previous_distance * 0.999);
    previous_distance = d;
  }
}

// Manual mode: quality - 2 levels, each half the triangles of the one before.
TEST(ChooseLevels, ManualQualityHalvesTheTriangles) {
  const TriangleMesh mesh = test::make_bumpy_sphere(11);
  const ChosenLevels chosen = choose_levels(mesh, radius_of(mesh), {.quality = 5});
  ASSERT_EQ(chosen.levels.size(), 3u);
  std::size_t target = mesh.triangle_count();
  for (const ChosenLevel& l : chosen.levels) {
    target /= 2;
    EXPECT_LE(l.measured.level.mesh.triangle_count(), target);
    EXPECT_GE(l.measured.level.mesh.triangle_count(), target * 9 / 10);
    EXPECT_EQ(l.switch_error, l.measured.error);
  }
}

TEST(ChooseLevels, LevelLimitEndsTheChainAndSaysSo) {
  const TriangleMesh mesh = test::make_bumpy_sphere(11);
  const double r = radius_of(mesh);
  const ChosenLevels all = choose_levels(mesh, r, {});
  ASSERT_GE(all.levels.size(), 2u);
  const ChosenLevels one = choose_levels(mesh, r, {.max_simplified = 1});
  ASSERT_EQ(one.levels.size(), 1u);
  EXPECT_EQ(one.stop_reason, "level limit (3 levels)");
}

TEST(ChooseLevels, BadCoordinatesAreADataError) {
  TriangleMesh mesh = test::make_bumpy_sphere(11);
  mesh.positions[0].x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(choose_levels(mesh, 1.0, {}), DataError);
}

}  // namespace
}  // namespace lodforge
