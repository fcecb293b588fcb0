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
}

}  // namespace
}  // namespace lodforge
