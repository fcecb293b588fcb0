#include "lodforge/simplify/out_of_core_clustering.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "core/temp_dir.h"
#include "lodforge/core/error.h"
#include "lodforge/core/morton.h"
#include "lodforge/core/quadric.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/metrics/compare_meshes.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

using ::testing::HasSubstr;

class OutOfCoreClusteringTest : public testing::TempDirTest {
 protected:
  /// Clusters `mesh` written as a binary file `name` (PLY or STL).
  OutOfCoreClusteringResult run(const TriangleMesh& mesh, const OutOfCoreClusteringOptions& options,
                                const std::string& name = "in.ply", std::size_t chunk = 1 << 16) {
    const std::string p = path(name);
    write_mesh(mesh, p);
    return out_of_core_clustering(TriangleStream(p, {.chunk_triangles = chunk}), options);
  }

  static const TriangleMesh& bunny() {
    static const TriangleMesh m = [] {
      const std::filesystem::path p =
          std::filesystem::path(LODFORGE_SHARED_DATA) / "meshes" / "bun_zipper.ply";
      return std::filesystem::exists(p) ? read_mesh(p.string()) : TriangleMesh{};
    }();
    return m;
  }
};

/// Every triangle has three distinct vertices and a non-zero area.
void expect_not_degenerate(const TriangleMesh& m) {
  for (std::size_t f = 0; f < m.triangle_count(); ++f) {
    const Triangle& t = m.triangles[f];
    ASSERT_TRUE(t[0] != t[1] && t[1] != t[2] && t[2] != t[0]) << f;
    ASSERT_GT(
        length(cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]])),
        0.0f)
        << f;
  }
}

// A mesh whose vertices lie in distinct cells comes back as it was: each
// tetrahedron corner is where three planes meet, the quadric's minimum.
TEST_F(OutOfCoreClusteringTest, FineGridKeepsATetrahedron) {
  const TriangleMesh tet = test::make_tetrahedron();
  const SimplifyResult r = run(tet, {.grid = 64});
  ASSERT_EQ(r.mesh.triangle_count(), 4u);
  ASSERT_EQ(r.mesh.vertex_count(), 4u);
  for (std::size_t v = 0; v < 4; ++v) {
    const Vec3 in = tet.positions[r.vertex_map[v]];
    EXPECT_NEAR(length(r.mesh.positions[v] - in), 0.0, 1e-6) << v;
  }
  EXPECT_LT(r.error, 1e-6);
  EXPECT_EQ(r.stop_reason, StopReason::kTargetReached);
  EXPECT_THAT(r.stop_detail, HasSubstr("grid 64 x"));
}

// One cell holds everything: no triangle spans three cells.
TEST_F(OutOfCoreClusteringTest, OneCellLeavesNothing) {
  const SimplifyResult r = run(test::make_cube(), {.grid = 1});
  EXPECT_EQ(r.mesh.triangle_count(), 0u);
  EXPECT_EQ(r.mesh.vertex_count(), 0u);
}

// An 8 x 8 grid of quads on [0,1]^2 clustered on a 2 x 2 grid of cells:
// the four cells' points are the means of their corners in the plane z = 0
// (the quadric is flat in x and y), and the two triangles around the centre
// are all that spans three cells, facing +z like the input.
TEST_F(OutOfCoreClusteringTest, PlanarGridOnTwoByTwoCells) {
  const SimplifyResult r = run(test::make_grid(8), {.grid = 2});
  ASSERT_EQ(r.mesh.vertex_count(), 4u);
  ASSERT_EQ(r.mesh.triangle_count(), 2u);
  for (const Vec3& p : r.mesh.positions) {
    EXPECT_EQ(p.z, 0.0f);
    // Cell [0, 0.5) holds grid lines 0..3 (mean 0.1875, weighted by corners);
    // cell [0.5, 1] lines 4..8.
    EXPECT_TRUE((p.x > 0.1f && p.x < 0.3f) || (p.x > 0.6f && p.x < 0.9f)) << p.x;
  }
  for (const Triangle& t : r.mesh.triangles) {
    const Vec3 n = cross(r.mesh.positions[t[1]] - r.mesh.positions[t[0]],
                         r.mesh.positions[t[2]] - r.mesh.positions[t[0]]);
    EXPECT_GT(n.z, 0.0f);
  }
  // The mesh is planar: every representative stays on it.
  EXPECT_LE(r.error, std::sqrt(2.0) * 0.5 + 1e-6);
}

/// Lindstrom's rule written plainly over a mesh in memory: cells of side
/// longest / grid from the box's low corner, area-weighted plane quadrics
/// summed per corner cell, triangles spanning three cells kept once per
/// oriented triple, each cell at its regularised quadric minimum about the
/// mean of its corners, clamped into the cell.
TriangleMesh reference(const TriangleMesh& m, std::uint32_t grid) {
  const Box3 box = m.bounds();
  const Vec3 size = box.size();
  const double h = std::max({double(size.x), double(size.y), double(size.z)}) / grid;
  std::array<std::uint32_t, 3> n;
  for (int a = 0; a < 3; ++a)
    n[a] = std::max<std::uint32_t>(1, std::uint32_t(std::ceil(double(size[a]) / h)));
  auto coords = [&](const Vec3& p) {
    std::array<std::uint32_t, 3> c;
    for (int a = 0; a < 3; ++a)
      c[a] = std::uint32_t(
          std::clamp(std::floor((double(p[a]) - box.lo[a]) / h), 0.0, double(n[a] - 1)));
    return c;
  };
  struct Cell {
    Quadric q{};
    std::array<double, 3> sum{};
    double corners = 0;
    std::array<std::uint32_t, 3> c{};
  };
  std::map<std::uint64_t, Cell> cells;
  std::set<std::array<std::uint64_t, 3>> kept;
  for (const Triangle& t : m.triangles) {
    const Vec3 &p = m.positions[t[0]], &q = m.positions[t[1]], &s = m.positions[t[2]];
    const double ux = double(q.x) - p.x, uy = double(q.y) - p.y, uz = double(q.z) - p.z;
    const double vx = double(s.x) - p.x, vy = double(s.y) - p.y, vz = double(s.z) - p.z;
    const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    std::array<std::uint64_t, 3> key;
    for (int k = 0; k < 3; ++k) {
      const Vec3& v = m.positions[t[k]];
      const auto c = coords(v);
      key[k] = morton_code(c[0], c[1], c[2]);
      Cell& cell = cells[key[k]];
      cell.c = c;
      if (len > 0) {
        const double d = -(nx * (p.x - box.lo.x) + ny * (p.y - box.lo.y) + nz * (p.z - box.lo.z));
        cell.q += Quadric::plane(nx, ny, nz, d, 0.5 / len);
      }
      for (int a = 0; a < 3; ++a) cell.sum[a] += double(v[a]) - box.lo[a];
      cell.corners += 1;
    }
    if (key[0] == key[1] || key[1] == key[2] || key[2] == key[0]) continue;
    while (key[0] > key[1] || key[0] > key[2]) key = {key[1], key[2], key[0]};
    kept.insert(key);
  }
  std::map<std::uint64_t, std::uint32_t> index;
  for (const auto& k : kept)
    for (std::uint64_t c : k) index[c] = 0;
  TriangleMesh out;
  for (auto& [key, i] : index) {
    const Cell& cell = cells[key];
    i = std::uint32_t(out.positions.size());
    auto x = quadric_minimum(cell.q, {cell.sum[0] / cell.corners, cell.sum[1] / cell.corners,
                                      cell.sum[2] / cell.corners});
    Vec3 p;
    for (int a = 0; a < 3; ++a)
      p[a] = float(std::clamp(x[a], cell.c[a] * h, (cell.c[a] + 1) * h) + box.lo[a]);
    out.positions.push_back(p);
  }
  for (const auto& k : kept) out.triangles.push_back({index[k[0]], index[k[1]], index[k[2]]});
  std::sort(out.triangles.begin(), out.triangles.end());
  return out;
}

// The bunny, written as binary PLY, gives what the plain rule gives.
TEST_F(OutOfCoreClusteringTest, BunnyMatchesThePlainRule) {
  if (bunny().triangle_count() == 0) GTEST_SKIP() << "bunny missing";
  for (std::uint32_t grid : {16u, 60u}) {
    SCOPED_TRACE(grid);
    const SimplifyResult r = run(bunny(), {.grid = grid});
    const TriangleMesh want = reference(bunny(), grid);
    ASSERT_EQ(r.mesh.triangles, want.triangles);
    ASSERT_EQ(r.mesh.vertex_count(), want.vertex_count());
    for (std::size_t v = 0; v < want.vertex_count(); ++v)
      ASSERT_LT(length(r.mesh.positions[v] - want.positions[v]), 1e-6f) << v;
    expect_not_degenerate(r.mesh);
  }
}

// With a ratio, the grid search lands between 0.7 and 1 times the target,
// and the result stays close to the bunny.
TEST_F(OutOfCoreClusteringTest, BunnyRatioLandsNearTheTarget) {
  if (bunny().triangle_count() == 0) GTEST_SKIP() << "bunny missing";
  for (float ratio : {0.1f, 0.01f}) {
    SCOPED_TRACE(ratio);
    const SimplifyResult r = run(bunny(), {.target = {.ratio = ratio}});
    const auto target = static_cast<std::size_t>(std::floor(ratio * 69451.0));
    EXPECT_EQ(r.stop_reason, StopReason::kTargetReached) << r.stop_detail;
    EXPECT_LE(r.mesh.triangle_count(), target);
    EXPECT_GE(double(r.mesh.triangle_count()), 0.7 * double(target));
    expect_not_degenerate(r.mesh);
    ASSERT_EQ(r.face_map.size(), r.mesh.triangle_count());
    ASSERT_EQ(r.vertex_map.size(), r.mesh.vertex_count());
    const CompareResult c = compare_meshes(bunny(), r.mesh);
    // The LODCreator's published mean deviations of its clustering at 90 %
    // and 99 % reduction (seed 000 Table 5.5, as in vertex_clustering_test),
    // in metres: Lindstrom's points beat them.
    EXPECT_LT(c.a_to_b.mean, ratio > 0.05f ? 2.00e-4 : 1.69e-3);
  }
}

// An error budget bounds the error; a count and a budget: the budget wins.
TEST_F(OutOfCoreClusteringTest, ErrorBudgetBoundsTheError) {
  if (bunny().triangle_count() == 0) GTEST_SKIP() << "bunny missing";
  const SimplifyResult e = run(bunny(), {.target = {.max_error = 0.004f}});
  EXPECT_LE(e.error, 0.004f);
  EXPECT_EQ(e.stop_reason, StopReason::kErrorBudgetReached);
  const SimplifyResult both = run(bunny(), {.target = {.triangles = 100, .max_error = 0.004f}});
  EXPECT_LE(both.error, 0.004f);
  EXPECT_GT(both.mesh.triangle_count(), 100u);
  EXPECT_EQ(both.stop_reason, StopReason::kErrorBudgetReached) << both.stop_detail;
}

// A budget finer than any vertex spacing keeps every triangle of an
// icosphere (81 920, more than the passes' cap for a count of 10): the
// pass the budget forces runs whole.
TEST_F(OutOfCoreClusteringTest, ErrorBudgetBeyondTheCapRunsWhole) {
  const TriangleMesh sphere = test::make_icosphere(6);
  const OutOfCoreClusteringResult r =
      run(sphere, {.target = {.triangles = 10, .max_error = 1e-5f}});
  EXPECT_EQ(r.mesh.triangle_count(), sphere.triangle_count());
  EXPECT_EQ(r.stop_reason, StopReason::kErrorBudgetReached) << r.stop_detail;
  EXPECT_EQ(r.passes, 3);  // the survey, the capped pass, the whole one
}

// Binary STL (every triangle its own corners) gives the same mesh as PLY;
// the result depends neither on the thread count nor on the chunk size.
TEST_F(OutOfCoreClusteringTest, SameResultForStlThreadsAndChunks) {
  if (bunny().triangle_count() == 0) GTEST_SKIP() << "bunny missing";
  const OutOfCoreClusteringOptions options{.target = {.ratio = 0.05f}};
  const SimplifyResult base = run(bunny(), options);
  const SimplifyResult stl = run(bunny(), options, "in.stl");
  EXPECT_EQ(stl.mesh.positions, base.mesh.positions);
  EXPECT_EQ(stl.mesh.triangles, base.mesh.triangles);
  EXPECT_EQ(stl.face_map, base.face_map);
  SimplifyResult one;
  {
    tbb::global_control only(tbb::global_control::max_allowed_parallelism, 1);
    one = run(bunny(), options, "in.ply", 777);
  }
  EXPECT_EQ(one.mesh.positions, base.mesh.positions);
  EXPECT_EQ(one.mesh.triangles, base.mesh.triangles);
  EXPECT_EQ(one.vertex_map, base.vertex_map);
  EXPECT_EQ(one.error, base.error);
}

TEST_F(OutOfCoreClusteringTest, EmptyAndBadInputs) {
  TriangleMesh points;
  points.positions = {{0, 0, 0}, {1, 1, 1}};
  const OutOfCoreClusteringResult r = run(points, {.target = {.ratio = 0.5f}});
  EXPECT_EQ(r.stop_reason, StopReason::kCannotSimplify);
  EXPECT_EQ(r.stop_detail, "the input has no triangles");
  // A file cut in its faces fails in the first pass, naming the file.
  write_mesh(test::make_cube(), path("cube.ply"));
  std::filesystem::resize_file(path("cube.ply"), std::filesystem::file_size(path("cube.ply")) - 3);
  EXPECT_THAT([&] { out_of_core_clustering(TriangleStream(path("cube.ply"))); },
              ::testing::ThrowsMessage<DataError>(HasSubstr("cube.ply: byte")));
}

}  // namespace
}  // namespace lodforge
