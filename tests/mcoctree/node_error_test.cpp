#include "lodforge/mcoctree/node_error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/cell_mesh.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/metrics/closest_point_on_triangle.h"
#include "lodforge/metrics/compare_meshes.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

const std::string kBunny = std::string(LODFORGE_SHARED_DATA) + "/meshes/bun_zipper.ply";

// Against a direct count on a sphere: each surface point belongs to the first
// leaf (in node order) that holds it; a node sums the distances from the
// points of all its descendant leaves to its own triangles, found here by
// walking the subtree rather than by the ranges of the Morton order.
// Then per level: the coarser the cells, the farther their chords.
TEST(NodeDistanceSums, MatchesASubtreeWalkAndGrowsWithCellSize) {
  auto round = build_mc_octree(test::make_icosphere(4), {.resolution = 32}).tree;
  auto sums = detail::node_distance_sums(round);
  ASSERT_EQ(sums.size(), round.nodes.size());
  std::vector<std::uint32_t> owner(round.positions.size(), McNode::kNone);
  for (std::uint32_t i = 0; i < round.nodes.size(); ++i)
    if (round.nodes[i].leaf())
      for (auto v : round.nodes[i].edge_vertex)
        if (v != McNode::kNone && owner[v] == McNode::kNone) owner[v] = i;
  std::size_t checked = 0;
  for (std::uint32_t i = 0; i < round.nodes.size(); ++i) {
    const McNode& n = round.nodes[i];
    if (n.leaf() || n.level < 3) continue;
    std::vector<Vec3> tris;
    detail::triangulate_node(
        round, n, 0, 0,
        [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
          for (auto v : {a, b, c}) tris.push_back(round.positions[v]);
        },
        [](const std::uint8_t*, int, std::uint16_t) { return McNode::kNone; });
    if (tris.empty()) continue;
    double want = 0;
    std::vector<std::uint32_t> stack{i};
    while (!stack.empty()) {
      const McNode& d = round.nodes[stack.back()];
      const std::uint32_t id = stack.back();
      stack.pop_back();
      for (int o = 0; o < 8; ++o)
        if (auto c = d.child(o); c != McNode::kNone) stack.push_back(c);
      if (!d.leaf()) continue;
      for (auto v : d.edge_vertex) {
        if (v == McNode::kNone || owner[v] != id) continue;
        float best = 1e30f;
        for (std::size_t t = 0; t < tris.size(); t += 3)
          best = std::min(
              best, closest_point_on_triangle(round.positions[v], tris[t], tris[t + 1], tris[t + 2])
                        .distance_squared);
        want += std::sqrt(best);
      }
    }
    EXPECT_NEAR(sums[i], want, 1e-4 * want + 1e-9) << "node " << i;
    ++checked;
  }
  EXPECT_GT(checked, 100u);

  // Per level: the mean distance per surface point under a node.
  std::vector<double> total(round.depth + 1, 0), nodes(round.depth + 1, 0);
  for (std::size_t i = 0; i < sums.size(); ++i) {
    const McNode& n = round.nodes[i];
    if (n.leaf()) EXPECT_EQ(sums[i], 0) << "node " << i;
    total[n.level] += sums[i];
    nodes[n.level] += !n.leaf();
  }
  // Every point is under exactly one node of each level above the leaves, so
  // a level's total is its mean distance times the point count. The coarsest
  // level's cell has no corner inside (no triangles: each point counts the
  // cell's diagonal); the next few cells are about the sphere's size, and
  // the least squares placement of their vertices (place_coarse_vertices)
  // serves some better than others; from where cells are well below the
  // sphere's size, finer is closer, by more than half.
  for (int l = 0; l < round.depth; ++l) std::printf("level %d: %.4g\n", l, total[l]);
  for (int l = 1; l < round.depth; ++l) EXPECT_LT(total[l], total[0]) << "level " << l;
  for (int l = round.depth - 3; l < round.depth; ++l)
    EXPECT_LT(total[l], 0.5 * total[l - 1]) << "level " << l;
  EXPECT_GT(total[round.depth - 1], 0);
}

// The priority numbering on the bunny (open, default resolution): no detail
// of the full-resolution model is lost down to 40 % with either metric (a
// coarser neighbour inherits a waiting node's metric), and the distance
// metric's mean deviation is below the area metric's at every level (its
// Hausdorff distance is not, since coarse vertices are placed off the
// surface: 0.89 against 0.73 % at 20 %).
TEST(NodeDistanceSums, DistanceMetricBeatsAreaOnTheBunny) {
  TriangleMesh bunny = read_mesh(kBunny);
  auto area = build_mc_octree(bunny, {}).tree;
  auto distance = build_mc_octree(bunny, {.metric = McPriorityMetric::kDistance}).tree;
  CompareOptions co{.samples = 30000, .per_vertex = false};
  auto larger_mean = [](const CompareResult& c) {
    return std::max(c.a_to_b.mean_pct, c.b_to_a.mean_pct);
  };
  const double full = compare_meshes(bunny, extract_mc_mesh(area).mesh, co).hausdorff_pct;
  std::printf("  %%   | area H %% / mean %% | distance H %% / mean %%   (full: H %.3f %%)\n", full);
  for (double pct : {80.0, 60.0, 40.0, 20.0, 5.0}) {
    auto ca = compare_meshes(bunny, extract_mc_mesh(area, {.percent = pct}).mesh, co);
    auto cd = compare_meshes(bunny, extract_mc_mesh(distance, {.percent = pct}).mesh, co);
    std::printf("  %4.0f | %7.3f / %7.4f | %7.3f / %7.4f\n", pct, ca.hausdorff_pct, larger_mean(ca),
                cd.hausdorff_pct, larger_mean(cd));
    if (pct >= 40) {
      EXPECT_LE(ca.hausdorff_pct, 1.05 * full) << pct << " %";
      EXPECT_LE(cd.hausdorff_pct, 1.05 * full) << pct << " %";
    }
    EXPECT_LT(larger_mean(cd), larger_mean(ca)) << pct << " %";
  }
}

}  // namespace
}  // namespace lodforge
