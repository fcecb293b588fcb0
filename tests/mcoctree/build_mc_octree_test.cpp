#include "lodforge/mcoctree/build_mc_octree.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/progress_recorder.h"
#include "lodforge/core/error.h"
#include "lodforge/mcoctree/cell_polygonize.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "lodforge/mesh/adjacency.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/metrics/compare_meshes.h"
#include "lodforge/metrics/triangle_bvh.h"
#include "lodforge/simplify/quadric_collapse.h"
#include "mcoctree/crack_check.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

TEST(BuildMcOctree, SphereLeavesLieOnTheSurface) {
  auto sphere = test::make_icosphere(3);
  auto r = build_mc_octree(sphere, {.resolution = 16, .place_coarse_vertices = false});
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

// Coarse levels' own vertices (McBuildOptions::place_coarse_vertices): the
// leaves keep the finest crossings, on the surface; a coarser level's vertex
// lies along its crossing's normal, within a quarter of its cell; every level
// edge has one vertex; on the sphere, whose
// coarse chords all cut inside, the coarse vertices move outwards.
TEST(BuildMcOctree, ReportsItsStages) {
  test::ProgressRecorder progress;
  build_mc_octree(test::make_icosphere(3), {.resolution = 32, .progress = progress.callback()});
  EXPECT_EQ(progress.stages(),
            (std::vector<std::string>{"signs", "surface points", "tree", "priorities"}));
  for (const auto& stage : progress.stages()) EXPECT_TRUE(progress.completed(stage)) << stage;
}

TEST(BuildMcOctree, CoarseVerticesStraddleTheSurface) {
  auto sphere = test::make_icosphere(4);
  const McOctree on = build_mc_octree(sphere, {.resolution = 24}).tree;
  const McOctree off =
      build_mc_octree(sphere, {.resolution = 24, .place_coarse_vertices = false}).tree;
  ASSERT_EQ(on.nodes.size(), off.nodes.size());
  EXPECT_GT(on.positions.size(), off.positions.size());
  std::vector<int> level(on.positions.size(), -1);
  std::size_t outwards = 0, moved = 0;
  for (std::size_t i = 0; i < on.nodes.size(); ++i) {
    const McNode &a = on.nodes[i], &b = off.nodes[i];
    const float limit = 0.25f * on.cell_size * static_cast<float>(1u << (on.depth - a.level));
    for (int e = 0; e < 12; ++e) {
      ASSERT_EQ(a.edge_vertex[e] == McNode::kNone, b.edge_vertex[e] == McNode::kNone);
      if (a.edge_vertex[e] == McNode::kNone) continue;
      const std::uint32_t v = a.edge_vertex[e];
      // One level per vertex: no two levels share one.
      EXPECT_TRUE(level[v] == -1 || level[v] == a.level) << "vertex " << v;
      level[v] = a.level;
      const Vec3 p = on.positions[v], q = off.positions[b.edge_vertex[e]];
      if (a.leaf()) {
        EXPECT_EQ(p, q);
        continue;
      }
      const Vec3 d = p - q;
      EXPECT_LE(length(d), limit * 1.0001f);
      EXPECT_LE(length(cross(d, on.normals[v])), 1e-4f * on.cell_size);  // along the normal
      moved += length(d) > 0;
      outwards += length(p) > length(q);
    }
  }
  EXPECT_GT(moved, 100u);
  EXPECT_GT(outwards, 0.95 * moved);
  // (Crack-free where levels meet: ExtractMcMesh.*IsCrackFreeAtEveryPriority
  // with the default options.)
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
  EXPECT_THROW(build_mc_octree(test::make_tetrahedron(), {.resolution = 1}), DataError);
  EXPECT_THROW(build_mc_octree(test::make_tetrahedron(), {.resolution = 1001}), DataError);
}

// Data the build cannot use is a DataError that says what is wrong.
TEST(BuildMcOctree, BadIndicesAndAttributesNameTheProblem) {
  auto expect_error = [](auto&& input, const std::string& text) {
    try {
      build_mc_octree(input);
      ADD_FAILURE() << "no error for " << text;
    } catch (const DataError& e) {
      EXPECT_THAT(e.what(), testing::HasSubstr(text));
    }
  };
  auto index = test::make_tetrahedron();
  index.triangles[2][1] = 4;
  expect_error(index, "triangle 2 has vertex index 4 out of range (4 vertices)");
  auto colours = test::make_tetrahedron();
  colours.colors.assign(3, Vec3{1, 0, 0});
  expect_error(colours, "3 colours for 4 vertices");
  // A range scan whose grid refers to a point it does not have, or whose
  // colours do not match its points.
  RangeScan scan{.name = "s.ply", .cols = 2, .rows = 1, .grid = {0, 5}};
  scan.points = {{0, 0, 0}, {1, 0, 0}};
  expect_error(std::vector<RangeScan>{scan}, "s.ply: grid index 5 out of range (2 points)");
  scan.grid = {0, 1};
  scan.colors = {Rgb8{1, 2, 3}};
  expect_error(std::vector<RangeScan>{scan}, "s.ply: 1 colours for 2 points");
}

// Coordinates out of the supported range, and a lattice past the memory
// budget, are refused before the work (with the estimate).
TEST(BuildMcOctree, RangeAndBudgetAreCheckedFirst) {
  for (float scale : {1e38f, 1e-38f}) {
    auto t = test::make_tetrahedron();
    for (auto& p : t.positions) p = p * scale;
    EXPECT_THROW(build_mc_octree(t), DataError);
  }
  const auto t = test::make_tetrahedron();
  const double bytes = mc_build_bytes(t.bounds(), 1000);
  EXPECT_GT(bytes, 4.5e9);
  EXPECT_LT(bytes, 5.5e9);
  try {
    build_mc_octree(t, {.resolution = 1000, .max_memory = std::uint64_t{1} << 30});
    ADD_FAILURE() << "no error";
  } catch (const DataError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("the lattice at resolution 1000 needs about 4.7 GiB, "
                                             "more than the memory budget of 1 GiB"));
  }
}

// An icosphere without its top (z > 0.5): a round hole, rim at z ~ 0.5.
TriangleMesh make_open_sphere() {
  auto sphere = test::make_icosphere(3);
  TriangleMesh open;
  open.positions = sphere.positions;
  for (const auto& f : sphere.triangles) {
    float z = 0;
    for (auto v : f) z = std::max(z, sphere.positions[v].z);
    if (z <= 0.5f) open.triangles.push_back(f);
  }
  return open;
}

// McHoles::kOpen: no surface over the hole at any priority, borders only
// along the input's rim, and otherwise crack-free (no T-junction, no
// non-manifold or inconsistent edge); McHoles::kCapped closes the hole.
TEST(BuildMcOctree, OpenMeshGetsBordersNotCaps) {
  auto open = make_open_sphere();
  TriangleBvh bvh(open);
  auto built = build_mc_octree(open, {.resolution = 24, .holes = McHoles::kOpen});
  const McOctree& t = built.tree;
  EXPECT_GT(built.stats.hole_nodes, 0u);
  const float h = t.cell_size;
  McExtractor ex(t);
  TriangleMesh m;
  for (std::uint32_t n = 1; n <= t.lod.size(); ++n) {
    if (ex.extract(n, m) == 0) continue;
    auto report = test::crack_report(m);
    ASSERT_EQ(report.t_junctions, 0u) << "priority " << n;
    ASSERT_EQ(report.topology.non_manifold_edges, 0u) << "priority " << n;
    ASSERT_EQ(report.topology.inconsistent_edges, 0u) << "priority " << n;
    ASSERT_GT(report.topology.boundary_edges, 0u) << "priority " << n;
  }
  // Full resolution: every point within a cell diagonal of the input, none
  // over the hole, and the borders at the rim.
  auto full = extract_mc_mesh(t).mesh;
  for (const auto& p : full.positions) {
    EXPECT_LE(std::sqrt(bvh.closest_point(p).distance_squared), 1.8f * h);
    EXPECT_LE(p.z, 0.5f + 2 * h);
  }
  auto adj = build_adjacency(full);
  ASSERT_GT(adj.boundary_edges.size(), 0u);
  for (auto e : adj.boundary_edges)
    for (auto v : adj.edges[e]) EXPECT_NEAR(full.positions[v].z, 0.5f, 3 * h);

  auto capped = build_mc_octree(open, {.resolution = 24, .holes = McHoles::kCapped}).tree;
  McExtractor cx(capped);
  for (std::uint32_t n = 1; n <= capped.lod.size(); ++n) {
    if (cx.extract(n, m) == 0) continue;
    auto report = test::crack_report(m);
    ASSERT_TRUE(report.ok()) << "capped, priority " << n << ": " << report.describe();
  }
}

// Resolution 0: about as many triangles at full resolution as the input.
TEST(BuildMcOctree, DefaultResolutionMatchesTheInputCount) {
  for (const auto& mesh : {test::make_icosphere(4), test::make_torus(1.0f, 0.3f, 96, 48)}) {
    auto r = build_mc_octree(mesh);
    EXPECT_GT(r.stats.resolution, 2);
    double ratio = static_cast<double>(r.tree.full_triangles()) / mesh.triangle_count();
    EXPECT_GT(ratio, 0.6);
    EXPECT_LT(ratio, 1.6);
    EXPECT_EQ(r.stats.hole_nodes, 0u);  // closed: nothing invented
    std::printf("default resolution %d: %llu triangles for %zu input triangles\n",
                r.stats.resolution, static_cast<unsigned long long>(r.tree.full_triangles()),
                mesh.triangle_count());
  }
}

// The Stanford bunny (open: holes in its bottom) with McHoles::kOpen at the
// default resolution: borders only along the input's rims, crack-free
// otherwise at 20 budgets, no cap at full resolution; and the quality table
// at 80 ... 5 % beside quadric collapse of the input and of the model's own
// full-resolution mesh to the same counts (printed; the 1.5x target is not
// asserted: it does not hold).
TEST(BuildMcOctree, BunnyHolesStayOpen) {
  const std::string path = std::string(LODFORGE_SHARED_DATA) + "/meshes/bun_zipper.ply";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " missing";
  auto bunny = read_mesh(path);
  auto built = build_mc_octree(bunny, {.holes = McHoles::kOpen});
  const McOctree& t = built.tree;
  const float h = t.cell_size;
  std::printf("bunny, default resolution %d: %llu triangles (input %zu), %zu hole nodes\n",
              built.stats.resolution, static_cast<unsigned long long>(t.full_triangles()),
              bunny.triangle_count(), built.stats.hole_nodes);
  // The input's rims as segments (degenerate triangles) for distances.
  TriangleMesh rims;
  rims.positions = bunny.positions;
  auto input_adj = build_adjacency(bunny);
  for (auto e : input_adj.boundary_edges)
    rims.triangles.push_back({input_adj.edges[e][0], input_adj.edges[e][1], input_adj.edges[e][1]});
  ASSERT_FALSE(rims.triangles.empty());
  TriangleBvh rim_bvh(rims);
  for (int step = 1; step <= 20; ++step) {
    auto r = extract_mc_mesh(t, {.percent = 5.0 * step});
    auto report = test::crack_report(r.mesh);
    ASSERT_EQ(report.t_junctions, 0u) << 5 * step << " %";
    ASSERT_EQ(report.topology.non_manifold_edges, 0u) << 5 * step << " %";
    ASSERT_EQ(report.topology.inconsistent_edges, 0u) << 5 * step << " %";
  }
  auto full = extract_mc_mesh(t).mesh;
  auto adj = build_adjacency(full);
  ASSERT_GT(adj.boundary_edges.size(), 0u);
  float worst = 0;
  for (auto e : adj.boundary_edges)
    for (auto v : adj.edges[e])
      worst = std::max(worst, std::sqrt(rim_bvh.closest_point(full.positions[v]).distance_squared));
  std::printf("full resolution: %zu border edges, farthest border point %.2f cells from a rim\n",
              adj.boundary_edges.size(), worst / h);
  EXPECT_LE(worst, 3 * h);

  std::printf(
      "  %%   | triangles | mco H %% / mean %% | qem(input) H / mean | ratio | qem(mco 100 %%) H "
      "/ mean | ratio\n");
  CompareOptions co{.samples = 50000, .per_vertex = false};
  auto mean = [](const CompareResult& c) { return (c.a_to_b.mean_pct + c.b_to_a.mean_pct) / 2; };
  for (double pct : {100.0, 80.0, 60.0, 40.0, 20.0, 5.0}) {
    auto m = extract_mc_mesh(t, {.percent = pct}).mesh;
    auto n = m.triangle_count();
    auto cm = compare_meshes(bunny, m, co);
    auto cq = compare_meshes(bunny, quadric_collapse(bunny, {.target = {.triangles = n}}).mesh, co);
    auto cf = compare_meshes(bunny, quadric_collapse(full, {.target = {.triangles = n}}).mesh, co);
    std::printf(
        "  %4.0f | %9zu | %7.3f / %7.4f | %7.3f / %7.4f | %5.1f / %5.1f | %7.3f / %7.4f | "
        "%4.2f / %4.2f\n",
        pct, n, cm.hausdorff_pct, mean(cm), cq.hausdorff_pct, mean(cq),
        cm.hausdorff_pct / cq.hausdorff_pct, mean(cm) / mean(cq), cf.hausdorff_pct, mean(cf),
        cm.hausdorff_pct / cf.hausdorff_pct, mean(cm) / mean(cf));
    if (pct == 100.0) EXPECT_LE(cm.hausdorff_pct, 1.0);  // caps made it 3.35 %
  }
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
