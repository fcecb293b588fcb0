// The one chain contract, asserted alike for the three methods.
#include "lodforge/simplify/level_chain.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lodforge/core/error.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

class LevelChain : public ::testing::TestWithParam<SimplifyMethod> {};

TEST_P(LevelChain, StepFromThePreviousResultDownToAFewTriangles) {
  const TriangleMesh mesh = test::make_torus(1.0f, 0.3f, 48, 24);  // 2 304 triangles
  const ChainTargets t{.step = 0.3f, .smallest = 4};
  const auto chain = simplify_chain(mesh, GetParam(), t);
  ASSERT_FALSE(chain.empty());
  std::size_t previous = mesh.triangle_count();
  for (std::size_t k = 0; k < chain.size(); ++k) {
    const std::size_t n = chain[k].mesh.triangle_count();
    EXPECT_GT(n, 0u) << "level " << k + 1 << " is empty";
    EXPECT_LE(double(n), std::max(std::floor(0.7 * double(previous)), 4.0)) << "level " << k + 1;
    if (k + 1 < chain.size()) EXPECT_EQ(chain[k].stop_reason, StopReason::kTargetReached);
    previous = n;
  }
  // The chain reaches a few percent, or says what stopped it.
  const SimplifyResult& last = chain.back();
  if (last.stop_reason == StopReason::kTargetReached)
    EXPECT_LE(last.mesh.triangle_count(), 4u);
  else
    EXPECT_FALSE(last.stop_detail.empty());
  EXPECT_LE(double(last.mesh.triangle_count()), 0.05 * double(mesh.triangle_count()));
}

TEST_P(LevelChain, ExplicitCountsAreEachMet) {
  const TriangleMesh mesh = test::make_icosphere(4);  // 5 120 triangles
  const std::vector<std::size_t> counts = {3000, 1500, 700, 300};
  const auto chain = simplify_chain(mesh, GetParam(), {.counts = counts});
  ASSERT_FALSE(chain.empty());
  ASSERT_LE(chain.size(), counts.size());
  std::size_t previous = mesh.triangle_count();
  for (std::size_t k = 0; k < chain.size(); ++k) {
    EXPECT_LE(chain[k].mesh.triangle_count(), counts[k]) << "level " << k + 1;
    EXPECT_LT(chain[k].mesh.triangle_count(), previous) << "level " << k + 1;
    previous = chain[k].mesh.triangle_count();
  }
}

TEST_P(LevelChain, NothingToRemoveGivesNoLevel) {
  EXPECT_TRUE(simplify_chain(test::make_tetrahedron(), GetParam(), {.smallest = 4}).empty());
  EXPECT_TRUE(simplify_chain(test::make_icosphere(2), GetParam(), {.step = 1.0f}).empty());
  EXPECT_TRUE(simplify_chain(TriangleMesh{}, GetParam(), {}).empty());
}

TEST_P(LevelChain, BadInputThrowsDataError) {
  TriangleMesh bad = test::make_icosphere(2);
  bad.triangles[3][1] = 100000;
  EXPECT_THROW(simplify_chain(bad, GetParam(), {}), DataError);
  TriangleMesh nan = test::make_icosphere(2);
  nan.positions[2].x = std::nanf("");
  EXPECT_THROW(simplify_chain(nan, GetParam(), {}), DataError);
}

// Quadric collapse aims each level at (1 - step) x the previous result, so
// no level is skipped: each lands at its target.
TEST(LevelChainQem, EachLevelLandsAtItsStepFromThePreviousResult) {
  const TriangleMesh mesh = test::make_icosphere(5);  // 20 480 triangles
  const auto chain = simplify_chain(mesh, SimplifyMethod::kQem, {.step = 0.2f});
  ASSERT_GE(chain.size(), 10u);
  std::size_t previous = mesh.triangle_count();
  for (std::size_t k = 0; k + 1 < chain.size(); ++k) {
    const double target = std::floor(0.8 * double(previous));
    EXPECT_GE(double(chain[k].mesh.triangle_count()), target - 4) << "level " << k + 1;
    previous = chain[k].mesh.triangle_count();
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, LevelChain,
                         ::testing::Values(SimplifyMethod::kCluster, SimplifyMethod::kDecimate,
                                           SimplifyMethod::kQem),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace lodforge
