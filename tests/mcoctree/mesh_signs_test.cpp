#include "lodforge/mcoctree/mesh_signs.h"

#include <gtest/gtest.h>

#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "lodforge/metrics/compare_meshes.h"
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

// The box [0,1]^3 whose top is a fan about its centre, one fan triangle
// replaced by a short flap whose tip `tip` sticks out beyond the side
// x = 1: the flap's underside (the face from the top's edge to the tip) is
// turned back against its two upper faces, so that the angle-weighted
// pseudo-normals at the tip and along its two edges cancel (a fold, as at
// horse.ply's tail tip, vertex 11891).
TriangleMesh make_box_with_folded_flap(Vec3 tip) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.push_back({float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)});
  m.positions.push_back({0.5f, 0.5f, 1});  // 8: the top's centre
  m.positions.push_back(tip);              // 9
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {0, 1, 5}, {0, 5, 4}, {1, 3, 7}, {1, 7, 5},
                 {3, 2, 6}, {3, 6, 7}, {2, 0, 4}, {2, 4, 6}, {8, 4, 5}, {8, 7, 6},
                 {8, 6, 4}, {8, 5, 9}, {5, 7, 9}, {7, 8, 9}};
  return m;
}

// The flap's tip a hair below the top (2^-22): its underside crosses its
// upper faces, turned back. Points beyond the tip are nearest it, where the
// pseudo-normal is rounding noise pointing into the box: taken at its word,
// a wedge of solid grows beyond the tip (1.3-2.0 cells from the input
// here). Taken as outside, the model's surface stays within a cell of the
// input.
TEST(SignedDistance, FoldTurnedBackMakesNoSolid) {
  const float below = -0x1p-22f;
  const SignedDistance sd(make_box_with_folded_flap({1.02f, 0.5f, 1 + below}));
  for (const Vec3& beyond : {Vec3{1.1f, 0.5f, 1}, Vec3{1.1f, 0.5f, 0.9f}, Vec3{1.1f, 0.5f, 1.1f}}) {
    const auto s = sd(beyond);
    EXPECT_FALSE(s.open);
    EXPECT_GT(s.distance, 0) << beyond.x << " " << beyond.y << " " << beyond.z;
  }
  EXPECT_LT(sd({0.5f, 0.5f, 0.9f}).distance, 0);
  for (auto [flap, resolution] : {std::pair{0.02f, 12}, {0.02f, 24}, {0.05f, 16}}) {
    const TriangleMesh box = make_box_with_folded_flap({1 + flap, 0.5f, 1 + below});
    const TriangleMesh full =
        extract_mc_mesh(build_mc_octree(box, {.resolution = resolution}).tree).mesh;
    const CompareResult c = compare_meshes(box, full, {.samples = 20000, .per_vertex = false});
    const float cell = (1 + flap) / float(resolution);
    EXPECT_LE(c.b_to_a.max, cell) << "flap " << flap << ", resolution " << resolution;
  }
}

}  // namespace
}  // namespace lodforge::detail
