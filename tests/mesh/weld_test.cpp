#include "lodforge/mesh/weld.h"

#include <gtest/gtest.h>

#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

TEST(Weld, CubeSoupBecomesTheCube) {
  TriangleMesh cube = test::make_cube();
  WeldResult r = weld(test::as_soup(cube));
  EXPECT_EQ(r.mesh.vertex_count(), 8u);
  EXPECT_EQ(r.mesh.triangle_count(), 12u);
  EXPECT_EQ(r.merged_vertices, 36u - 8u);
  ASSERT_EQ(r.remap.size(), 36u);
  for (std::size_t f = 0; f < 12; ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(r.mesh.positions[r.mesh.triangles[f][k]], cube.positions[cube.triangles[f][k]]);
}

TEST(Weld, NegativeZeroEqualsZero) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {-0.0f, 0, -0.0f}, {1, 0, 0}};
  WeldResult r = weld(m);
  EXPECT_EQ(r.mesh.vertex_count(), 2u);
  EXPECT_EQ(r.remap, (std::vector<std::uint32_t>{0, 0, 1}));
}

TEST(Weld, NearbyVerticesMergeOnlyWithEpsilon) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1e-5f, 0, 0}, {1, 1e-5f, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  WeldResult exact = weld(m);
  EXPECT_EQ(exact.mesh.vertex_count(), 5u);
  WeldResult loose = weld(m, {.epsilon = 1e-4f, .remove_duplicates = true});
  EXPECT_EQ(loose.mesh.vertex_count(), 3u);
  EXPECT_EQ(loose.removed_duplicates, 1u);
  EXPECT_EQ(loose.mesh.triangle_count(), 1u);
  EXPECT_EQ(loose.face_origin, (std::vector<std::uint32_t>{0}));
}

TEST(Weld, EpsilonWorksAcrossCellBorders) {
  TriangleMesh m;
  m.positions = {{0.99999f, 0, 0}, {1.00001f, 0, 0}};
  EXPECT_EQ(weld(m, {.epsilon = 1e-3f}).mesh.vertex_count(), 1u);
}

TEST(Weld, DegenerateTrianglesAndLinesAreDropped) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.materials = {5, 6};
  m.lines = {{0, 1}, {2, 3}, {3, 2}};
  WeldResult r = weld(m);
  EXPECT_EQ(r.removed_degenerate, 1u);
  ASSERT_EQ(r.mesh.triangle_count(), 1u);
  EXPECT_EQ(r.mesh.materials, (std::vector<std::uint32_t>{6}));
  EXPECT_EQ(r.mesh.lines.size(), 2u);
  WeldResult d = weld(m, {.remove_duplicates = true});
  EXPECT_EQ(d.mesh.lines.size(), 1u);
  EXPECT_EQ(d.removed_lines, 2u);
  WeldResult keep = weld(m, {.remove_degenerate = false});
  EXPECT_EQ(keep.mesh.triangle_count(), 2u);
}

TEST(Weld, DuplicatesUpToRotationButNotMirror) {
  TriangleMesh m = test::make_tetrahedron();
  m.triangles.push_back({1, 2, 0});  // rotation of the first
  m.triangles.push_back({0, 2, 1});  // the back side: kept
  WeldResult r = weld(m, {.remove_duplicates = true});
  EXPECT_EQ(r.removed_duplicates, 1u);
  EXPECT_EQ(r.mesh.triangle_count(), 5u);
}

TEST(Weld, AttributeSeamsSurviveWhenAsked) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {0, 0, 0}, {1, 0, 0}};
  m.texcoords = {{0, 0}, {1, 0}, {0.5f, 0}};
  EXPECT_EQ(weld(m).mesh.vertex_count(), 2u);
  WeldResult r = weld(m, {.match_attributes = true});
  EXPECT_EQ(r.mesh.vertex_count(), 3u);
  EXPECT_EQ(r.mesh.texcoords.size(), 3u);
}

TEST(Weld, AttributesFollowTheKeptVertex) {
  TriangleMesh m = test::make_grid(3);
  TriangleMesh doubled = m;
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    doubled.positions.push_back(m.positions[i]);
    doubled.normals.push_back(m.normals[i]);
    doubled.texcoords.push_back(m.texcoords[i]);
  }
  auto nv = static_cast<std::uint32_t>(m.vertex_count());
  for (const Triangle& t : m.triangles)
    doubled.triangles.push_back({t[0] + nv, t[1] + nv, t[2] + nv});
  WeldResult r = weld(doubled, {.match_attributes = true, .remove_duplicates = true});
  EXPECT_EQ(r.mesh.vertex_count(), m.vertex_count());
  EXPECT_EQ(r.mesh.triangles, m.triangles);
  EXPECT_EQ(r.mesh.texcoords, m.texcoords);
}

TEST(Weld, EmptyMesh) {
  WeldResult r = weld(TriangleMesh{});
  EXPECT_EQ(r.mesh.vertex_count(), 0u);
  EXPECT_TRUE(r.remap.empty());
}

TEST(Weld, LargeSoupIsLinear) {
  TriangleMesh big = test::as_soup(test::make_icosphere(6));  // 81920 triangles
  WeldResult r = weld(big);
  EXPECT_EQ(r.mesh.vertex_count(), 40962u);
  EXPECT_EQ(r.mesh.triangle_count(), 81920u);
}

}  // namespace
}  // namespace lodforge
