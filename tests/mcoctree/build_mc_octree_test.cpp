#include "lodforge/mcoctree/build_mc_octree.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lodforge/core/error.h"
#include "lodforge/mcoctree/cell_polygonize.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "lodforge/mesh/adjacency.h"
#include "mcoctree/crack_check.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

TEST(BuildMcOctree, SphereLeavesLieOnTheSurface) {
  auto sphere = test::make_icosphere(3);
  auto r = build_mc_octree(sphere, {.resolution = 16});
  const McOctree& t = r.tree;
  ASSERT_FALSE(t.nodes.empty());
  EXPECT_EQ(t.depth, 5);                // 16 + 2 cells -> 32
  EXPECT_EQ(r.stats.sign_repairs, 0u);  // closed mesh: the flood fill agrees
  for (std::size_t v = 0; v < t.positions.size(); ++v) {
    EXPECT_NEAR(length(t.positions[v]), 1.0f, 0.02f);
    EXPECT_GT(dot(t.normals[v], t.positions[v]), 0.9f);
  }
  // Priorities: a permutation of the internal nodes, root first.
  EXPECT_EQ(t.lod.front(), 0u);
  std::size_t internal = 0;
  for (const auto& n : t.nodes) internal += !n.leaf();
  EXPECT_EQ(t.lod.size(), internal);
  for (std::size_t i = 0; i < t.lod.size(); ++i) EXPECT_EQ(t.nodes[t.lod[i]].priority, i + 1);
  // A child is expanded after its parent.
  for (const auto& n : t.nodes)
    for (int o = 0; o < 8; ++o)
      if (auto c = n.child(o); c != McNode::kNone && !t.nodes[c].leaf())
        EXPECT_GT(t.nodes[c].priority, n.priority);
}

TEST(BuildMcOctree, FourCaseRuleMatchesChildren) {
  auto torus = test::make_torus(1.0f, 0.3f, 32, 16);
  auto t = build_mc_octree(torus, {.resolution = 20}).tree;
  // Every parent corner equals the sign of the child corner at the same point
  // wherever that child exists (case 1), and each edge point is a child's.
  for (const auto& n : t.nodes) {
    if (n.leaf()) continue;
    for (int o = 0; o < 8; ++o) {
      auto c = n.child(o);
      if (c == McNode::kNone) continue;
      int p = detail::corner_point(o);
      EXPECT_EQ(n.signs27 >> p & 1, t.nodes[c].signs27 >> detail::corner_point(o) & 1);
    }
  }
}

TEST(BuildMcOctree, BadInput) {
  EXPECT_THROW(build_mc_octree(TriangleMesh{}), DataError);
  auto nan = test::make_tetrahedron();
  nan.positions[1].y = std::nanf("");
  EXPECT_THROW(build_mc_octree(nan), DataError);
  auto point = test::make_tetrahedron();
  for (auto& p : point.positions) p = {1, 2, 3};
  EXPECT_THROW(build_mc_octree(point), DataError);
  EXPECT_THROW(build_mc_octree(test::make_tetrahedron(), {.resolution = 1}), std::invalid_argument);
}

TEST(ExtractMcMesh, SphereIsCrackFreeAtEveryPriority) {
  auto sphere = test::make_icosphere(3);
  auto t = build_mc_octree(sphere, {.resolution = 24}).tree;
  McExtractor ex(t);
  TriangleMesh m;
  for (std::uint32_t n = 1; n <= t.lod.size(); ++n) {
    std::size_t tris = ex.extract(n, m);
    ASSERT_EQ(tris, t.accumulated[n]) << "priority " << n;
    if (tris == 0) continue;
    auto report = test::crack_report(m);
    ASSERT_TRUE(report.ok()) << "priority " << n << ": " << report.describe();
  }
}

TEST(ExtractMcMesh, TorusIsCrackFreeAtEveryPriority) {
  auto torus = test::make_torus(1.0f, 0.3f, 48, 24);
  auto t = build_mc_octree(torus, {.resolution = 28}).tree;
  McExtractor ex(t);
  TriangleMesh m;
  for (std::uint32_t n = 1; n <= t.lod.size(); ++n) {
    std::size_t tris = ex.extract(n, m);
    ASSERT_EQ(tris, t.accumulated[n]) << "priority " << n;
    if (tris == 0) continue;
    auto report = test::crack_report(m);
    ASSERT_TRUE(report.ok()) << "priority " << n << ": " << report.describe();
  }
  // The full level has the torus's genus.
  auto full = extract_mc_mesh(t);
  EXPECT_EQ(mesh_topology_report(full.mesh).euler_characteristic(), 0);
}

}  // namespace
}  // namespace lodforge
