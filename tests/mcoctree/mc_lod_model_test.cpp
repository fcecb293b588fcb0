#include "lodforge/mcoctree/mc_lod_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/cell_mesh.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "mcoctree/crack_check.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

using PositionTriangle = std::array<std::array<float, 3>, 3>;

// A triangle by its corner positions, rotated so that the smallest corner
// comes first (orientation kept).
PositionTriangle canonical(Vec3 a, Vec3 b, Vec3 c) {
  PositionTriangle t{{{a.x, a.y, a.z}, {b.x, b.y, b.z}, {c.x, c.y, c.z}}};
  auto first = std::min_element(t.begin(), t.end()) - t.begin();
  std::rotate(t.begin(), t.begin() + first, t.end());
  return t;
}

// The thesis's walk straight on the tree (what extraction did before the
// run-time model): for N down to 1, triangulate each child of the node of
// priority N that is not expanded itself, with its faces and edges split by
// the split priorities <= N.
std::vector<PositionTriangle> reference_walk(const McOctree& t, std::uint32_t N) {
  std::vector<PositionTriangle> out;
  auto cell = [&](const McNode& n) {
    std::uint16_t halved = 0;
    std::uint8_t split = 0;
    for (int e = 0; e < 12; ++e) halved |= static_cast<std::uint16_t>((n.edge_split[e] <= N) << e);
    for (int f = 0; f < 6; ++f) split |= static_cast<std::uint8_t>((n.face_split[f] <= N) << f);
    std::vector<Vec3> centroids;
    constexpr std::uint32_t kCentroid = 0x80000000u;
    auto position = [&](std::uint32_t v) {
      return v & kCentroid ? centroids[v & ~kCentroid] : t.positions[v];
    };
    detail::triangulate_node(
        t, n, halved, split,
        [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
          out.push_back(canonical(position(a), position(b), position(c)));
        },
        [&](const std::uint8_t* slots, int count, std::uint16_t h) {
          Vec3 p{};
          for (int k = 0; k < count; ++k) p += t.positions[detail::slot_vertex(t, n, slots[k], h)];
          centroids.push_back(p / static_cast<float>(count));
          return static_cast<std::uint32_t>(centroids.size() - 1) | kCentroid;
        });
  };
  if (N == 0) {
    cell(t.nodes[0]);
    return out;
  }
  for (std::uint32_t i = N; i >= 1; --i) {
    const McNode& n = t.nodes[t.lod[i - 1]];
    for (int o = 0; o < 8; ++o)
      if (auto c = n.child(o); c != McNode::kNone && t.nodes[c].priority > N) cell(t.nodes[c]);
  }
  return out;
}

std::vector<PositionTriangle> index_triangles(const McLodModel& m,
                                              const std::vector<Triangle>& tris) {
  std::vector<PositionTriangle> out;
  for (const auto& f : tris)
    out.push_back(canonical(m.positions[f[0]], m.positions[f[1]], m.positions[f[2]]));
  return out;
}

// At every priority: the index buffer holds exactly the reference walk's
// triangles (same positions, same orientation), accumulated[N] of them, and
// is crack-free.
void check_every_priority(const McOctree& tree) {
  McLodModel m = compile_mc_lod(tree);
  ASSERT_EQ(m.priorities(), tree.lod.size());
  ASSERT_EQ(m.group.size(), tree.lod.size() + 2);
  std::vector<Triangle> tris;
  for (std::uint32_t n = 0; n <= m.priorities(); ++n) {
    std::size_t count = extract_mc_indices(m, n, tris);
    ASSERT_EQ(count, tree.accumulated[n]) << "priority " << n;
    ASSERT_EQ(tris.size(), count);
    auto got = index_triangles(m, tris);
    auto want = reference_walk(tree, n);
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    ASSERT_EQ(got, want) << "priority " << n;
    if (count == 0) continue;
    TriangleMesh mesh;
    mesh.positions = m.positions;
    mesh.triangles = tris;
    auto report = test::crack_report(mesh);
    ASSERT_TRUE(report.ok()) << "priority " << n << ": " << report.describe();
  }
  std::printf(
      "%u priorities, %zu cells, %zu intervals, %zu stored triangles for %llu at full "
      "resolution, %zu vertices (%zu centroids), %.1f bytes per full-resolution triangle\n",
      m.priorities(), m.cell_count(), m.intervals.size() - 1, m.stored_triangles(),
      static_cast<unsigned long long>(m.full_triangles()), m.positions.size(), m.centroids.size(),
      static_cast<double>(m.memory_bytes()) / static_cast<double>(m.full_triangles()));
}

TEST(McLodModel, SphereMatchesTheTreeWalkAtEveryPriority) {
  check_every_priority(build_mc_octree(test::make_icosphere(3), {.resolution = 24}).tree);
}

TEST(McLodModel, TorusMatchesTheTreeWalkAtEveryPriority) {
  check_every_priority(
      build_mc_octree(test::make_torus(1.0f, 0.3f, 48, 24), {.resolution = 28}).tree);
}

// The shape of the model: cells grouped by their parent's priority, each
// cell's intervals starting at its group and increasing below its `until`,
// every vertex used, and the index buffer beyond the last priority clamped.
TEST(McLodModel, Structure) {
  auto tree = build_mc_octree(test::make_torus(1.0f, 0.35f, 32, 16), {.resolution = 20}).tree;
  McLodModel m = compile_mc_lod(tree);
  const std::uint32_t L = m.priorities();
  ASSERT_EQ(m.group.front(), 0u);
  ASSERT_EQ(m.group.back(), m.cell_count());
  std::vector<bool> used(m.positions.size(), false);
  std::vector<int> expanded(L + 1, 0);
  for (std::uint32_t k = 0; k <= L; ++k)
    for (std::uint32_t c = m.group[k]; c < m.group[k + 1]; ++c) {
      const McLodCell& cell = m.cells[c];
      EXPECT_GT(cell.until, k);
      if (cell.until <= L) ++expanded[cell.until];
      const std::uint32_t i0 = cell.first_interval, i1 = m.cells[c + 1].first_interval;
      ASSERT_LT(i0, i1);
      EXPECT_EQ(m.intervals[i0].from, k);
      for (std::uint32_t i = i0; i < i1; ++i) {
        if (i > i0) EXPECT_GT(m.intervals[i].from, m.intervals[i - 1].from);
        EXPECT_LT(m.intervals[i].from, cell.until);
        for (std::uint32_t t = m.intervals[i].first_triangle; t < m.intervals[i + 1].first_triangle;
             ++t)
          for (auto v : m.triangles[t]) used[v] = true;
      }
    }
  for (std::uint32_t k = 1; k <= L; ++k) EXPECT_EQ(expanded[k], 1) << "priority " << k;
  EXPECT_EQ(std::count(used.begin(), used.end(), false), 0);
  EXPECT_TRUE(std::is_sorted(m.centroids.begin(), m.centroids.end()));
  std::vector<Triangle> tris;
  EXPECT_EQ(extract_mc_indices(m, L + 1000, tris), m.full_triangles());
  EXPECT_EQ(extract_mc_indices(McLodModel{}, 5, tris), 0u);
  EXPECT_TRUE(tris.empty());
}

TEST(McLodModel, NormalEncodingIsWithinTwentiethOfADegree) {
  std::mt19937 rng(7);
  std::normal_distribution<float> g;
  double worst = 0;
  std::vector<Vec3> dirs = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int i = 0; i < 100000; ++i) dirs.push_back(normalized(Vec3{g(rng), g(rng), g(rng)}));
  for (Vec3 n : dirs) {
    Vec3 d = decode_normal(encode_normal(n));
    EXPECT_NEAR(length(d), 1.0f, 1e-5f);
    double angle = std::acos(std::clamp(static_cast<double>(dot(d, n)), -1.0, 1.0)) * 180 / M_PI;
    worst = std::max(worst, angle);
  }
  std::printf("worst normal error %.5f degrees\n", worst);
  EXPECT_LT(worst, 0.05);
  EXPECT_EQ(decode_normal(encode_normal(Vec3{})).z, 1.0f);  // zero: +z
}

}  // namespace
}  // namespace lodforge
