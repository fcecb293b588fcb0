#include "lodforge/simplify/vertex_clustering.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "lodforge/core/error.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/metrics/compare_meshes.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

/// A "book": `pages` triangles sharing the edge (0,0,0)-(0,0,1) (a
/// non-manifold edge), plus a second fan touching the first only at the
/// origin (a non-manifold vertex).
TriangleMesh make_non_manifold_fan(int pages = 5) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {0, 0, 1}};
  for (int i = 0; i < pages; ++i) {
    float a = float(2 * kPi * i / pages);
    m.positions.push_back({std::cos(a), std::sin(a), 0.5f});
    m.triangles.push_back({0, 1, std::uint32_t(2 + i)});
  }
  auto base = static_cast<std::uint32_t>(m.positions.size());
  m.positions.push_back({-0.5f, -0.5f, -1});
  m.positions.push_back({0.5f, -0.5f, -1});
  m.positions.push_back({0, 0.7f, -1});
  m.triangles.push_back({0, base, base + 1});
  m.triangles.push_back({0, base + 1, base + 2});
  m.triangles.push_back({0, base + 2, base});
  return m;
}

/// A helix polyline of `n` points: a line set without triangles.
TriangleMesh make_helix_lines(int n = 200) {
  TriangleMesh m;
  for (int i = 0; i < n; ++i) {
    float t = float(i) * 0.1f;
    m.positions.push_back({std::cos(t), std::sin(t), 0.05f * t});
    if (i > 0) m.lines.push_back({std::uint32_t(i - 1), std::uint32_t(i)});
  }
  return m;
}

/// The invariants every level of every chain keeps.
void expect_valid_chain(const TriangleMesh& input, const std::vector<SimplifyResult>& chain,
                        float min_diff = 0.2f) {
  ASSERT_FALSE(chain.empty());
  for (std::size_t l = 0; l < chain.size(); ++l) {
    SCOPED_TRACE("level " + std::to_string(l));
    const SimplifyResult& r = chain[l];
    const TriangleMesh& m = r.mesh;
    ASSERT_EQ(r.vertex_map.size(), m.vertex_count());
    ASSERT_EQ(r.face_map.size(), m.triangle_count());
    std::vector<char> used(m.vertex_count(), 0);
    std::set<std::array<std::uint32_t, 3>> tris;
    for (const Triangle& t : m.triangles) {
      for (std::uint32_t v : t) {
        ASSERT_LT(v, m.vertex_count());
        used[v] = 1;
      }
      ASSERT_TRUE(t[0] != t[1] && t[1] != t[2] && t[2] != t[0]) << "collapsed triangle kept";
      auto r0 = std::min_element(t.begin(), t.end()) - t.begin();
      std::array<std::uint32_t, 3> key{t[r0], t[(r0 + 1) % 3], t[(r0 + 2) % 3]};
      EXPECT_TRUE(tris.insert(key).second) << "doublet kept";
    }
    std::set<std::pair<std::uint32_t, std::uint32_t>> lines;
    for (const Segment& s : m.lines) {
      ASSERT_LT(s[0], m.vertex_count());
      ASSERT_LT(s[1], m.vertex_count());
      ASSERT_NE(s[0], s[1]);
      used[s[0]] = used[s[1]] = 1;
      EXPECT_TRUE(lines.insert({std::min(s[0], s[1]), std::max(s[0], s[1])}).second);
      for (const Triangle& t : m.triangles) {
        bool has0 = std::find(t.begin(), t.end(), s[0]) != t.end();
        bool has1 = std::find(t.begin(), t.end(), s[1]) != t.end();
        EXPECT_FALSE(has0 && has1) << "line equal to a triangle edge kept";
      }
    }
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
      EXPECT_TRUE(used[v]) << "unused vertex " << v;
      ASSERT_LT(r.vertex_map[v], input.vertex_count());
      EXPECT_TRUE(is_finite(m.positions[v]));
    }
    for (std::uint32_t f : r.face_map) ASSERT_LT(f, input.triangle_count());
    if (l == 0) {
      EXPECT_EQ(r.error, 0.f);
    } else {
      auto limit = static_cast<std::size_t>(
          std::floor((1.0 - min_diff) * double(chain[l - 1].mesh.vertex_count())));
      EXPECT_LE(m.vertex_count(), limit) << "min diff rule";
      EXPECT_LT(m.vertex_count(), chain[l - 1].mesh.vertex_count());
      EXPECT_GE(r.error, 0.f);
    }
    EXPECT_FALSE(r.stop_detail.empty());
  }
}

TEST(VertexClustering, GridChainStaysInThePlane) {
  TriangleMesh grid = test::make_grid(16);
  std::vector<SimplifyResult> chain = vertex_clustering(grid);
  expect_valid_chain(grid, chain);
  ASSERT_GE(chain.size(), 3u);
  EXPECT_EQ(chain[0].mesh.vertex_count(), 17u * 17u);
  EXPECT_EQ(chain[0].mesh.triangle_count(), 2u * 16u * 16u);
  EXPECT_EQ(chain[0].stop_reason, StopReason::kNoReduction);
  // The last level is the octree of depth 1: at most 8 (here 4) cells.
  EXPECT_LE(chain.back().mesh.vertex_count(), 4u);
  EXPECT_EQ(chain.back().stop_reason, StopReason::kCannotSimplify);
  for (const SimplifyResult& r : chain) {
    for (const Vec3& p : r.mesh.positions) {
      EXPECT_EQ(p.z, 0.f);
      EXPECT_GE(p.x, 0.f);
      EXPECT_LE(p.x, 1.f);
      EXPECT_GE(p.y, 0.f);
      EXPECT_LE(p.y, 1.f);
    }
  }
  for (std::size_t l = 1; l < chain.size(); ++l) {
    EXPECT_LT(chain[l].mesh.triangle_count(), chain[l - 1].mesh.triangle_count());
    EXPECT_EQ(chain[l].stop_reason,
              l + 1 < chain.size() ? StopReason::kTargetReached : StopReason::kCannotSimplify);
  }
}

TEST(VertexClustering, ChainFollowsTheMinDiffRule) {
  TriangleMesh sphere = test::make_icosphere(4);
  for (float min_diff : {0.0f, 0.2f, 0.5f, 0.9f}) {
    SCOPED_TRACE(min_diff);
    std::vector<SimplifyResult> chain = vertex_clustering(sphere, {.min_diff = min_diff});
    expect_valid_chain(sphere, chain, min_diff);
    EXPECT_GE(chain.size(), 2u);
  }
  // min diff 100 %: no level can drop all vertices, level 0 alone.
  std::vector<SimplifyResult> one = vertex_clustering(sphere, {.min_diff = 1.0f});
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].stop_reason, StopReason::kCannotSimplify);
  // A smaller min diff gives at least as many levels.
  EXPECT_GE(vertex_clustering(sphere, {.min_diff = 0.05f}).size(),
            vertex_clustering(sphere, {.min_diff = 0.5f}).size());
}

TEST(VertexClustering, TriangleSoupClustersLikeTheWeldedMesh) {
  TriangleMesh sphere = test::make_icosphere(3);
  TriangleMesh s = test::as_soup(sphere);
  std::vector<SimplifyResult> a = vertex_clustering(sphere);
  std::vector<SimplifyResult> b = vertex_clustering(s);
  expect_valid_chain(s, b);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(b[0].mesh.vertex_count(), sphere.vertex_count());
  for (std::size_t l = 0; l < a.size(); ++l) {
    EXPECT_EQ(a[l].mesh.vertex_count(), b[l].mesh.vertex_count());
    EXPECT_EQ(a[l].mesh.triangle_count(), b[l].mesh.triangle_count());
    EXPECT_EQ(a[l].mesh.positions, b[l].mesh.positions);
  }
}

TEST(VertexClustering, NonManifoldFanAndDegenerateInput) {
  TriangleMesh fan = make_non_manifold_fan();
  expect_valid_chain(fan, vertex_clustering(fan));

  // Degenerate and duplicate triangles, a T-junction, an unused vertex.
  TriangleMesh m = test::make_grid(4);
  m.normals.clear();
  m.texcoords.clear();
  m.triangles.push_back(m.triangles[3]);                                             // doublet
  m.triangles.push_back({m.triangles[3][1], m.triangles[3][2], m.triangles[3][0]});  // rotated
  m.triangles.push_back({0, 0, 1});          // collapsed to a line
  m.triangles.push_back({2, 2, 2});          // collapsed to a point
  m.positions.push_back({0.5f, 0.5f, 0.f});  // duplicate coordinate
  m.positions.push_back({7, 7, 7});          // unused
  m.triangles.push_back({std::uint32_t(m.positions.size() - 2), 1, 2});
  std::vector<SimplifyResult> chain = vertex_clustering(m);
  expect_valid_chain(m, chain);
  EXPECT_EQ(chain[0].mesh.vertex_count(), 25u);  // the duplicate merged, the unused dropped
  EXPECT_EQ(chain[0].mesh.triangle_count(), 32u + 1u);
}

TEST(VertexClustering, UnusedVertexBesideTheFarCorner) {
  // The used corner (1, 1, 1) quantises to the bounding cube's far corner,
  // whose Morton code shares its top bits with an unused vertex's marker:
  // the unused vertex (listed first) must still sort last and be cut off.
  TriangleMesh m;
  m.positions = {{5, 5, 5}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1}, {0, 0, 1}};
  m.triangles = {{1, 2, 3}, {1, 3, 4}, {1, 4, 2}, {2, 4, 3}, {1, 5, 2}};
  std::vector<SimplifyResult> chain = vertex_clustering(m);
  expect_valid_chain(m, chain);
  ASSERT_EQ(chain[0].mesh.vertex_count(), 5u);
  for (std::uint32_t v : chain[0].vertex_map) EXPECT_NE(v, 0u);
}

TEST(VertexClustering, CollapsedTrianglesBecomeLines) {
  // A sliver: corners 1 and 2 share the deepest cell and merge first.
  TriangleMesh sliver;
  sliver.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0.001f, 0}};
  sliver.triangles = {{0, 1, 2}};
  std::vector<SimplifyResult> chain = vertex_clustering(sliver);
  expect_valid_chain(sliver, chain);
  ASSERT_GE(chain.size(), 2u);
  EXPECT_EQ(chain[1].mesh.triangle_count(), 0u);
  ASSERT_EQ(chain[1].mesh.lines.size(), 1u);
  EXPECT_EQ(chain[1].mesh.vertex_count(), 2u);

  // With no_lines the next level would be empty: level 0 alone.
  std::vector<SimplifyResult> none = vertex_clustering(sliver, {.no_lines = true});
  ASSERT_EQ(none.size(), 1u);
  EXPECT_EQ(none[0].stop_reason, StopReason::kCannotSimplify);

  // A triangle collapsing onto an edge of a kept triangle leaves no line.
  TriangleMesh pair;
  pair.positions = {{0, 0, 0}, {1, 0, 0}, {0.5f, 1, 0}, {1, -0.0001f, 0}};
  pair.triangles = {{0, 1, 2}, {0, 3, 1}};
  chain = vertex_clustering(pair);
  expect_valid_chain(pair, chain);
  ASSERT_GE(chain.size(), 2u);
  EXPECT_EQ(chain[1].mesh.vertex_count(), 3u);
  EXPECT_EQ(chain[1].mesh.triangle_count(), 1u);
  EXPECT_TRUE(chain[1].mesh.lines.empty());
  EXPECT_EQ(chain[1].face_map, std::vector<std::uint32_t>{0});
}

TEST(VertexClustering, LineSetUsesTheWeightedMean) {
  TriangleMesh helix = make_helix_lines();
  std::vector<SimplifyResult> chain = vertex_clustering(helix);
  expect_valid_chain(helix, chain);
  ASSERT_GE(chain.size(), 4u);
  EXPECT_EQ(chain[0].mesh.lines.size(), 199u);
  for (const SimplifyResult& r : chain) {
    EXPECT_EQ(r.mesh.triangle_count(), 0u);
    EXPECT_FALSE(r.mesh.lines.empty());
    // Representatives are input vertices (no quadric point without faces).
    for (std::size_t v = 0; v < r.mesh.vertex_count(); ++v)
      EXPECT_EQ(r.mesh.positions[v], helix.positions[r.vertex_map[v]]);
  }
  // The weighted mean alone picks the same as any weights without faces.
  std::vector<SimplifyResult> mean_only = vertex_clustering(
      helix, {.area_weight = 0, .volume_weight = 0, .mean_weight = 1, .quadric_weight = 0});
  ASSERT_EQ(mean_only.size(), chain.size());
  for (std::size_t l = 0; l < chain.size(); ++l)
    EXPECT_EQ(mean_only[l].mesh.positions, chain[l].mesh.positions);
}

TEST(VertexClustering, AttributesFollowRepresentativesAndFaces) {
  TriangleMesh grid = test::make_grid(8);
  grid.colors.resize(grid.vertex_count());
  for (std::size_t v = 0; v < grid.vertex_count(); ++v)
    grid.colors[v] = {float(v) / float(grid.vertex_count()), 0.5f, 1.f};
  grid.materials.resize(grid.triangle_count());
  for (std::size_t f = 0; f < grid.triangle_count(); ++f) grid.materials[f] = std::uint32_t(f % 3);
  for (float quadric_weight : {0.f, 8.f}) {
    std::vector<SimplifyResult> chain = vertex_clustering(grid, {.quadric_weight = quadric_weight});
    expect_valid_chain(grid, chain);
    for (const SimplifyResult& r : chain) {
      ASSERT_EQ(r.mesh.normals.size(), r.mesh.vertex_count());
      ASSERT_EQ(r.mesh.texcoords.size(), r.mesh.vertex_count());
      ASSERT_EQ(r.mesh.colors.size(), r.mesh.vertex_count());
      ASSERT_EQ(r.mesh.materials.size(), r.mesh.triangle_count());
      for (std::size_t v = 0; v < r.mesh.vertex_count(); ++v) {
        EXPECT_EQ(r.mesh.normals[v], grid.normals[r.vertex_map[v]]);
        EXPECT_EQ(r.mesh.texcoords[v], grid.texcoords[r.vertex_map[v]]);
        EXPECT_EQ(r.mesh.colors[v], grid.colors[r.vertex_map[v]]);
        if (quadric_weight == 0) EXPECT_EQ(r.mesh.positions[v], grid.positions[r.vertex_map[v]]);
      }
      for (std::size_t f = 0; f < r.mesh.triangle_count(); ++f)
        EXPECT_EQ(r.mesh.materials[f], grid.materials[r.face_map[f]]);
    }
  }
}

TEST(VertexClustering, TargetsStopTheChain) {
  TriangleMesh sphere = test::make_icosphere(4);  // 5120 triangles
  std::vector<SimplifyResult> full = vertex_clustering(sphere);

  std::vector<SimplifyResult> by_ratio = vertex_clustering(sphere, {.target = {.ratio = 0.1f}});
  ASSERT_GE(by_ratio.size(), 2u);
  EXPECT_LE(by_ratio.back().mesh.triangle_count(), 512u);
  EXPECT_GT(by_ratio[by_ratio.size() - 2].mesh.triangle_count(), 512u);
  EXPECT_EQ(by_ratio.back().stop_reason, StopReason::kTargetReached);
  EXPECT_LE(by_ratio.size(), full.size());

  std::vector<SimplifyResult> by_count = vertex_clustering(sphere, {.target = {.triangles = 512}});
  EXPECT_EQ(by_count.size(), by_ratio.size());

  const float budget = full[2].error;
  std::vector<SimplifyResult> by_error =
      vertex_clustering(sphere, {.target = {.max_error = budget}});
  for (const SimplifyResult& r : by_error) EXPECT_LE(r.error, budget);
  EXPECT_EQ(by_error.back().stop_reason, StopReason::kErrorBudgetReached);
  EXPECT_EQ(by_error.size(), 3u);

  std::vector<SimplifyResult> none = vertex_clustering(sphere, {.target = {.ratio = 1.0f}});
  ASSERT_EQ(none.size(), 1u);
  EXPECT_EQ(none[0].stop_reason, StopReason::kNoReduction);
  EXPECT_EQ(none[0].mesh.triangle_count(), sphere.triangle_count());
}

TEST(VertexClustering, ErrorIsTheLargestVertexDisplacement) {
  TriangleMesh sphere = test::make_uv_sphere(32, 16);
  std::vector<SimplifyResult> chain = vertex_clustering(sphere);
  // Every representative lies within its cell, so the displacement is at
  // most the cell diagonal, and the unit sphere's cube has side 2.
  for (std::size_t l = 1; l < chain.size(); ++l) {
    const SimplifyResult& r = chain[l];
    EXPECT_GT(r.error, 0.f);
    EXPECT_LE(r.error, std::sqrt(3.f) * 2.f);
    // The representative of an original vertex is at most `error` away:
    // a level's vertex is within `error` of the original it stands for.
    for (std::size_t v = 0; v < r.mesh.vertex_count(); ++v)
      EXPECT_LE(length(r.mesh.positions[v] - sphere.positions[r.vertex_map[v]]), r.error * 1.0001f);
  }
}

/// Each level's error recomputed from scratch: the octree as the
/// implementation sets it up (the used vertices' box, its largest side, 21
/// bits per axis), each input vertex's cell at the level's depth (read from
/// its detail), the level's vertex in that cell (the one whose source vertex
/// lies there), and the largest distance of an input vertex still stood for
/// (used, and its cell never lost its vertex) to it. The implementation
/// skips vertices a bound says cannot be the farthest: its figure must still
/// be exactly this one.
TEST(VertexClustering, ErrorIsExactlyTheLargestDisplacement) {
  for (const TriangleMesh& mesh : {test::make_uv_sphere(32, 16), test::make_icosphere(4),
                                   test::as_soup(test::make_icosphere(3))}) {
    const std::vector<SimplifyResult> chain = vertex_clustering(mesh);
    ASSERT_GE(chain.size(), 3u);
    Box3 box;
    std::vector<char> alive(mesh.vertex_count(), 0);
    for (const Triangle& t : mesh.triangles)
      for (std::uint32_t v : t) box.add(mesh.positions[v]), alive[v] = 1;
    const Vec3 size = box.size();
    const double scale =
        double(1u << 21) / std::max({double(size.x), double(size.y), double(size.z)});
    auto cell = [&](const Vec3& p, int depth) {
      std::uint64_t key = 0;
      for (int a = 0; a < 3; ++a) {
        const double q = (double(p[a]) - box.lo[a]) * scale;
        const auto qi = static_cast<std::uint32_t>(std::min(q, double((1u << 21) - 1)));
        key = key << 21 | qi >> (21 - depth);
      }
      return key;
    };
    for (std::size_t l = 1; l < chain.size(); ++l) {
      const SimplifyResult& r = chain[l];
      int depth = 0;
      ASSERT_EQ(std::sscanf(r.stop_detail.c_str(), "octree depth %d", &depth), 1) << r.stop_detail;
      std::map<std::uint64_t, std::uint32_t> vertex_of;
      for (std::uint32_t v = 0; v < r.mesh.vertex_count(); ++v)
        EXPECT_TRUE(vertex_of.emplace(cell(mesh.positions[r.vertex_map[v]], depth), v).second);
      double largest2 = 0;
      for (std::uint32_t i = 0; i < mesh.vertex_count(); ++i) {
        if (!alive[i]) continue;
        auto it = vertex_of.find(cell(mesh.positions[i], depth));
        if (it == vertex_of.end()) {
          alive[i] = 0;
          continue;
        }
        const Vec3 d = mesh.positions[i] - r.mesh.positions[it->second];
        largest2 = std::max(largest2, double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z);
      }
      EXPECT_EQ(r.error, float(std::sqrt(largest2))) << "level " << l << ": " << r.stop_detail;
    }
  }
}

TEST(VertexClustering, EmptyAndBadInput) {
  std::vector<SimplifyResult> empty = vertex_clustering(TriangleMesh{});
  ASSERT_EQ(empty.size(), 1u);
  EXPECT_EQ(empty[0].mesh.vertex_count(), 0u);
  EXPECT_EQ(empty[0].stop_reason, StopReason::kCannotSimplify);

  TriangleMesh point;  // one triangle, all corners equal
  point.positions = {{1, 2, 3}, {1, 2, 3}, {1, 2, 3}};
  point.triangles = {{0, 1, 2}};
  std::vector<SimplifyResult> p = vertex_clustering(point);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].mesh.triangle_count(), 0u);

  TriangleMesh bad = test::make_tetrahedron();
  bad.triangles.push_back({0, 1, 9});
  EXPECT_THROW(vertex_clustering(bad), DataError);
  TriangleMesh nan = test::make_tetrahedron();
  nan.positions[2].y = std::nanf("");
  EXPECT_THROW(vertex_clustering(nan), DataError);
  // Only used coordinates must be finite: an unused one is never quantised.
  TriangleMesh unused_nan = test::make_tetrahedron();
  unused_nan.positions.push_back({std::nanf(""), std::numeric_limits<float>::infinity(), 0});
  std::vector<SimplifyResult> u = vertex_clustering(unused_nan);
  EXPECT_EQ(u[0].mesh.vertex_count(), 4u);
}

TEST(VertexClustering, RandomSoupsNeverBreakTheRules) {
  std::mt19937 rng(7);
  for (int round = 0; round < 40; ++round) {
    TriangleMesh m;
    int nv = 1 + int(rng() % 60);
    std::uniform_real_distribution<float> coord(-1, 1);
    for (int v = 0; v < nv; ++v) {
      // Few distinct values: many equal coordinates and collinear points.
      if (rng() % 3 == 0)
        m.positions.push_back({float(rng() % 3), float(rng() % 3), 0});
      else
        m.positions.push_back({coord(rng), coord(rng), coord(rng)});
    }
    int nf = int(rng() % 120);
    for (int f = 0; f < nf; ++f)
      m.triangles.push_back(
          {std::uint32_t(rng() % nv), std::uint32_t(rng() % nv), std::uint32_t(rng() % nv)});
    int nl = int(rng() % 10);
    for (int l = 0; l < nl; ++l)
      m.lines.push_back({std::uint32_t(rng() % nv), std::uint32_t(rng() % nv)});
    SCOPED_TRACE("round " + std::to_string(round));
    expect_valid_chain(m, vertex_clustering(m));
    expect_valid_chain(m, vertex_clustering(m, {.quadric_weight = 0, .no_lines = true}));
  }
}

TEST(VertexClustering, ResultDoesNotDependOnTheThreadCount) {
  TriangleMesh sphere = test::make_icosphere(5);
  std::vector<SimplifyResult> many = vertex_clustering(sphere);
  std::vector<SimplifyResult> one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = vertex_clustering(sphere);
  }
  ASSERT_EQ(many.size(), one.size());
  for (std::size_t l = 0; l < many.size(); ++l) {
    EXPECT_EQ(many[l].mesh.positions, one[l].mesh.positions);
    EXPECT_EQ(many[l].mesh.triangles, one[l].mesh.triangles);
    EXPECT_EQ(many[l].vertex_map, one[l].vertex_map);
  }
}

// Each heuristic is normalised over the cell, and a candidate leaves the
// contest when its weighted quadric term exceeds the best by more than the
// other weights sum to: both depend only on the ratios of the weights.
TEST(VertexClustering, OnlyTheRatiosOfTheWeightsMatter) {
  TriangleMesh sphere = test::make_icosphere(5);
  std::vector<SimplifyResult> base = vertex_clustering(sphere, {.mean_weight = 2});
  // x4 keeps every product and quotient exact.
  std::vector<SimplifyResult> scaled = vertex_clustering(
      sphere, {.area_weight = 32, .volume_weight = 4, .mean_weight = 8, .quadric_weight = 128});
  ASSERT_EQ(base.size(), scaled.size());
  for (std::size_t l = 0; l < base.size(); ++l) {
    EXPECT_EQ(base[l].mesh.positions, scaled[l].mesh.positions);
    EXPECT_EQ(base[l].vertex_map, scaled[l].vertex_map);
  }
}

// The bunny of the LODCreator thesis (its Table 5.5): the level closest to
// each reduction must beat the LODCreator's published clustering figures.
TEST(VertexClustering, BunnyBeatsTheThesis) {
  const std::filesystem::path path =
      std::filesystem::path(LODFORGE_SHARED_DATA) / "meshes" / "bun_zipper.ply";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " missing";
  TriangleMesh bunny = read_mesh(path.string());
  ASSERT_EQ(bunny.triangle_count(), 69451u);
  std::vector<SimplifyResult> chain = vertex_clustering(bunny);
  expect_valid_chain(bunny, chain);
  struct Bar {
    double reduction;
    double thesis_mean;  // metres
  };
  for (Bar bar : {Bar{0.50, 4.17e-5}, Bar{0.90, 2.00e-4}, Bar{0.99, 1.69e-3}}) {
    double want = (1 - bar.reduction) * double(bunny.triangle_count());
    const SimplifyResult* best = &chain[0];
    for (const SimplifyResult& r : chain)
      if (std::abs(double(r.mesh.triangle_count()) - want) <
          std::abs(double(best->mesh.triangle_count()) - want))
        best = &r;
    CompareResult c = compare_meshes(bunny, best->mesh);
    double mean = std::max(c.a_to_b.mean, c.b_to_a.mean);
    std::printf(
        "bunny %2.0f%%: level %zu, %6zu triangles (%.2f %% reduction), mean %.3e (thesis "
        "%.2e), hausdorff %.3e, error %.3e\n",
        100 * bar.reduction, std::size_t(best - chain.data()), best->mesh.triangle_count(),
        100.0 * (1.0 - double(best->mesh.triangle_count()) / double(bunny.triangle_count())), mean,
        bar.thesis_mean, c.hausdorff, double(best->error));
    EXPECT_LT(mean, bar.thesis_mean) << "at " << 100 * bar.reduction << " % reduction";
  }
}

}  // namespace
}  // namespace lodforge
