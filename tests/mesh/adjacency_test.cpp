#include "lodforge/mesh/adjacency.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

TEST(Adjacency, CubeIsClosedAndManifold) {
  TriangleMesh cube = test::make_cube();
  MeshAdjacency a = build_adjacency(cube);
  EXPECT_EQ(a.edges.size(), 18u);
  EXPECT_TRUE(a.boundary_edges.empty());
  EXPECT_TRUE(a.non_manifold_edges.empty());
  for (std::uint32_t e = 0; e < a.edges.size(); ++e) {
    EXPECT_LT(a.edges[e][0], a.edges[e][1]);
    EXPECT_EQ(a.edge_valence(e), 2u);
  }
  std::size_t incident = 0;
  for (std::uint32_t v = 0; v < 8; ++v) incident += a.triangles_of_vertex(v).size();
  EXPECT_EQ(incident, 36u);
  TopologyReport r = mesh_topology_report(cube);
  EXPECT_TRUE(r.closed());
  EXPECT_TRUE(r.manifold());
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.euler_characteristic(), 2);
  EXPECT_EQ(r.inconsistent_edges, 0u);
}

TEST(Adjacency, TriangleEdgesPointToTheirSides) {
  TriangleMesh m = test::make_icosphere(1);
  MeshAdjacency a = build_adjacency(m);
  for (std::uint32_t f = 0; f < m.triangle_count(); ++f)
    for (int k = 0; k < 3; ++k) {
      std::uint32_t e = a.triangle_edges[f][k];
      std::uint32_t u = m.triangles[f][k], w = m.triangles[f][(k + 1) % 3];
      EXPECT_EQ(a.edges[e], (Segment{std::min(u, w), std::max(u, w)}));
      EXPECT_EQ(a.find_edge(u, w), e);
      auto tris = a.triangles_of_edge(e);
      EXPECT_TRUE(std::find(tris.begin(), tris.end(), f) != tris.end());
    }
  EXPECT_EQ(a.find_edge(0, 0), MeshAdjacency::kNoEdge);
}

TEST(Adjacency, GridHasOneBoundaryLoop) {
  TriangleMesh g = test::make_grid(4);
  TopologyReport r = mesh_topology_report(g);
  EXPECT_EQ(r.boundary_edges, 16u);
  EXPECT_EQ(r.boundary_loops, 1u);
  EXPECT_EQ(r.euler_characteristic(), 1);
  EXPECT_TRUE(r.manifold());
  EXPECT_FALSE(r.closed());
}

TEST(Adjacency, TorusHasEulerZero) {
  TopologyReport r = mesh_topology_report(test::make_torus());
  EXPECT_TRUE(r.closed());
  EXPECT_EQ(r.euler_characteristic(), 0);
  EXPECT_EQ(r.inconsistent_edges, 0u);
}

TEST(Adjacency, FinEdgeIsNonManifold) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  MeshAdjacency a = build_adjacency(m);
  ASSERT_EQ(a.non_manifold_edges.size(), 1u);
  EXPECT_EQ(a.edges[a.non_manifold_edges[0]], (Segment{0, 1}));
  EXPECT_EQ(a.boundary_edges.size(), 6u);
  TopologyReport r = mesh_topology_report(m);
  EXPECT_EQ(r.non_manifold_edges, 1u);
  EXPECT_FALSE(r.manifold());
}

TEST(Adjacency, BowtieVertexIsNonManifold) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  m.triangles = {{0, 1, 2}, {0, 3, 4}};
  TopologyReport r = mesh_topology_report(m);
  EXPECT_EQ(r.non_manifold_vertices, 1u);
  EXPECT_EQ(r.non_manifold_edges, 0u);
  EXPECT_EQ(r.components, 1u);
}

TEST(Adjacency, ComponentsIsolatedAndFlipped) {
  TriangleMesh m = test::make_tetrahedron();
  TriangleMesh c = test::make_cube();
  auto base = static_cast<std::uint32_t>(m.vertex_count());
  m.positions.insert(m.positions.end(), c.positions.begin(), c.positions.end());
  for (const Triangle& t : c.triangles)
    m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  m.positions.push_back({5, 5, 5});                 // isolated
  std::swap(m.triangles[0][1], m.triangles[0][2]);  // flip one face
  m.triangles.push_back({0, 0, 0});                 // degenerate
  TopologyReport r = mesh_topology_report(m);
  EXPECT_EQ(r.components, 2u);
  EXPECT_EQ(r.isolated_vertices, 1u);
  EXPECT_EQ(r.inconsistent_edges, 3u);
  EXPECT_EQ(r.degenerate_triangles, 1u);
}

TEST(Adjacency, EmptyMesh) {
  MeshAdjacency a = build_adjacency(TriangleMesh{});
  EXPECT_TRUE(a.edges.empty());
  EXPECT_EQ(a.vertex_offsets.size(), 1u);
  TopologyReport r = mesh_topology_report(TriangleMesh{});
  EXPECT_EQ(r.components, 0u);
}

TEST(TestMeshes, ClosedBuildersAreOutward) {
  for (const TriangleMesh& m :
       {test::make_tetrahedron(), test::make_cube(), test::make_icosphere(2),
        test::make_uv_sphere(), test::make_torus()}) {
    EXPECT_GT(test::signed_volume(m), 0);
    TopologyReport r = mesh_topology_report(m);
    EXPECT_TRUE(r.closed());
    EXPECT_TRUE(r.manifold());
    EXPECT_EQ(r.inconsistent_edges, 0u);
  }
  EXPECT_EQ(test::make_icosphere(2).vertex_count(), 162u);
  EXPECT_EQ(mesh_topology_report(test::make_open_disk(16)).boundary_edges, 16u);
}

// Parts: triangles joined by a vertex or by a vertex position (split seams),
// numbered in the order of their first triangle.
TEST(TriangleParts, SharedVerticesAndPositionsJoin) {
  TriangleMesh two = test::make_cube(1.f);
  const TriangleMesh far = test::make_cube(1.f, {5, 0, 0});
  const auto base = std::uint32_t(two.positions.size());
  two.positions.insert(two.positions.end(), far.positions.begin(), far.positions.end());
  for (Triangle t : far.triangles) two.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  const std::vector<std::uint32_t> parts = triangle_parts(two);
  ASSERT_EQ(parts.size(), 24u);
  EXPECT_EQ(parts.front(), 0u);
  EXPECT_EQ(parts.back(), 1u);
  EXPECT_EQ(*std::max_element(parts.begin(), parts.end()), 1u);
  // Every triangle with its own corners (a triangle soup): still one part
  // per cube, by the positions the corners share.
  EXPECT_EQ(triangle_parts(test::as_soup(two)), parts);
  EXPECT_TRUE(triangle_parts(TriangleMesh{}).empty());
}

}  // namespace
}  // namespace lodforge
