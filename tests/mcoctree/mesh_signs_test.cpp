#include "lodforge/mcoctree/mesh_signs.h"

#include <gtest/gtest.h>

#include "mesh/test_meshes.h"

namespace lodforge::detail {
namespace {

// The cube [0,2]^3: negative inside, positive outside, the side right at an
// edge and a corner by the pseudo-normal.
TEST(SignedDistance, CubeSidesByPseudoNormal) {
  const SignedDistance sd(test::make_cube(2));
  EXPECT_FALSE(sd.has_rims());
  EXPECT_FLOAT_EQ(sd({1, 1, 1}).distance, -1);
  EXPECT_FLOAT_EQ(sd({1, 1, 3}).distance, 1);
  EXPECT_FLOAT_EQ(sd({3, 3, 1}).distance, std::sqrt(2.0f));  // off an edge
  EXPECT_FLOAT_EQ(sd({3, 3, 3}).distance, std::sqrt(3.0f));  // off a corner
  EXPECT_NEAR(sd({1.9f, 1.9f, 1.9f}).distance, -0.1f, 1e-6f);
  // The hint never changes the answer.
  for (std::uint32_t hint = 0; hint < 12; ++hint)
    EXPECT_EQ(sd({3, 3, 3}, hint).at.triangle, sd({3, 3, 3}).at.triangle);
}

// An open disk: points nearest its rim have no side.
TEST(SignedDistance, OpenRimHasNoSide) {
  const SignedDistance sd(test::make_open_disk());
  EXPECT_TRUE(sd.has_rims());
  EXPECT_FALSE(sd({0, 0, 0.5f}).open);
  const auto beyond = sd({2, 0, 0.5f});
  EXPECT_TRUE(beyond.open);
  EXPECT_GT(beyond.distance, 0);
}

// The cube's lattice: inside points are those inside the cube, and every
// point next to the surface has an exact distance.
TEST(MakeMeshLattice, CubeSignsMatchTheCube) {
  const SignedDistance sd(test::make_cube(2));
  McBuildStats stats;
  const Lattice lat = make_mesh_lattice(sd, 8, stats, {});
  EXPECT_GT(stats.band_points, 0u);
  std::size_t inside = 0;
  for (std::int64_t idx = 0; idx < static_cast<std::int64_t>(lat.state.size()); ++idx) {
    const Vec3 p = lat.point(idx);
    const bool in = p.x > 0 && p.x < 2 && p.y > 0 && p.y < 2 && p.z > 0 && p.z < 2;
    EXPECT_EQ(lat.inside(idx), in) << idx;
    inside += in;
    EXPECT_TRUE(lat.state[idx] & kAssigned);
  }
  EXPECT_GT(inside, 0u);
  EXPECT_TRUE(std::is_sorted(lat.distance.begin(), lat.distance.end()));
}

TEST(MeshResolution, AboutAsManyTrianglesAsTheInput) {
  // Few large triangles: the lowest resolution; a finer icosphere: more cells.
  EXPECT_EQ(mesh_resolution(test::make_tetrahedron()), 2);
  EXPECT_GT(mesh_resolution(test::make_icosphere(4)), mesh_resolution(test::make_icosphere(2)));
}

}  // namespace
}  // namespace lodforge::detail
