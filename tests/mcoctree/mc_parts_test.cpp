// Whether a model keeps the input's parts: counts and the model's smallest
// parts.
#include "lodforge/mcoctree/mc_parts.h"

#include <gtest/gtest.h>

#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

TriangleMesh joined(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh out = a;
  const auto base = std::uint32_t(out.positions.size());
  out.positions.insert(out.positions.end(), b.positions.begin(), b.positions.end());
  for (Triangle t : b.triangles) out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  return out;
}

TEST(McParts, CountsAndTheSmallestPartsWhereTheyDiffer) {
  const TriangleMesh cube = test::make_cube(1.f);
  const TriangleMesh small = test::make_cube(0.1f, {3, 0, 0});
  EXPECT_TRUE(check_mc_parts(cube, cube).kept());
  EXPECT_TRUE(check_mc_parts(cube, cube).smallest.empty());
  // The model came apart: two parts where the input had one; the smallest
  // first, with its bounds.
  const McPartsCheck apart = check_mc_parts(cube, joined(cube, joined(small, cube)), 2);
  EXPECT_FALSE(apart.kept());
  EXPECT_EQ(apart.input_parts, 1u);
  EXPECT_EQ(apart.model_parts, 2u);  // the second cube shares the first's positions
  ASSERT_EQ(apart.smallest.size(), 2u);
  EXPECT_EQ(apart.smallest[0].triangles, 12u);
  EXPECT_FLOAT_EQ(apart.smallest[0].bounds.lo.x, 3.f);
  EXPECT_FLOAT_EQ(apart.smallest[0].bounds.hi.x, 3.1f);
  EXPECT_EQ(apart.smallest[1].triangles, 24u);
  // Parts joined: fewer in the model.
  const McPartsCheck closed = check_mc_parts(joined(cube, small), cube);
  EXPECT_EQ(closed.input_parts, 2u);
  EXPECT_EQ(closed.model_parts, 1u);
  EXPECT_TRUE(closed.vanished.empty());  // not looked for
}

// An input part no model part comes within `near` of has vanished; the
// resolution that keeps it makes it two cells across its thinnest side.
TEST(McParts, NamesTheVanishedPartsAndTheResolutionThatKeepsThem) {
  const TriangleMesh cube = test::make_cube(1.f);
  const TriangleMesh input = joined(cube, test::make_cube(0.1f, {3, 0, 0}));
  const McPartsCheck gone = check_mc_parts(input, cube, 3, 0.2f);
  ASSERT_EQ(gone.vanished.size(), 1u);
  EXPECT_EQ(gone.vanished[0].triangles, 12u);
  EXPECT_FLOAT_EQ(gone.vanished[0].bounds.lo.x, 3.f);
  EXPECT_EQ(resolution_to_keep(gone.vanished[0], input.bounds()), 62);  // 2 x 3.1 / 0.1
  // A model part within `near` stands for an input part: of three input
  // parts, only the one with none near has vanished.
  const TriangleMesh three = joined(input, test::make_cube(0.1f, {0, 3, 0}));
  const TriangleMesh nearby = joined(cube, test::make_cube(0.1f, {3.15f, 0, 0}));
  const McPartsCheck one = check_mc_parts(three, nearby, 3, 0.2f);
  ASSERT_EQ(one.vanished.size(), 1u);
  EXPECT_FLOAT_EQ(one.vanished[0].bounds.lo.y, 3.f);
  // Flat: no resolution keeps it.
  McPart flat{.triangles = 2, .bounds = Box3{{0, 0, 0}, {1, 1, 0}}};
  EXPECT_GT(resolution_to_keep(flat, input.bounds()), 1000);
}

}  // namespace
}  // namespace lodforge
