#include "lodforge/simplify/detail/clustering_level0.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <array>
#include <filesystem>
#include <set>

#include "lodforge/core/error.h"
#include "lodforge/mesh/mesh_io.h"
#include "mesh/test_meshes.h"

namespace lodforge::detail::clustering {
namespace {

TriangleMesh bunny() {
  const std::filesystem::path path =
      std::filesystem::path(LODFORGE_SHARED_DATA) / "meshes" / "bun_zipper.ply";
  return read_mesh(path.string());
}

struct Level0 {
  Cut cut;
  Octree octree;
};

Level0 level0(const TriangleMesh& mesh, bool no_lines = false) {
  Level0 l;
  RemapScratch scratch;
  l.octree = build_level0(mesh, no_lines, l.cut, scratch);
  return l;
}

/// The same vertices (positions, codes, and input vertices when `same_input`)
/// and triangles.
void expect_same_level(const Cut& a, const Cut& b, bool same_input) {
  EXPECT_EQ(a.pos, b.pos);
  EXPECT_EQ(a.code, b.code);
  if (same_input) EXPECT_EQ(a.orig, b.orig);
  EXPECT_EQ(a.tris, b.tris);
  EXPECT_EQ(a.tri_origin, b.tri_origin);
}

TEST(ClusteringLevel0, BunnyIsInOctreeOrderWithItsTrianglesSortedBySmallestCorner) {
  const TriangleMesh mesh = bunny();
  const Level0 l = level0(mesh);
  std::set<std::array<float, 3>> used;
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t v : t)
      used.insert({mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z});
  EXPECT_EQ(l.cut.size(), used.size());  // one vertex per distinct used coordinate
  EXPECT_EQ(l.cut.tris.size(), mesh.triangle_count());
  for (std::size_t i = 1; i < l.cut.size(); ++i) ASSERT_LE(l.cut.code[i - 1], l.cut.code[i]) << i;
  for (std::size_t v = 0; v < l.cut.size(); ++v)
    ASSERT_EQ(l.cut.pos[v], mesh.positions[l.cut.orig[v]]) << v;
  auto smallest = [](const Triangle& t) { return std::min({t[0], t[1], t[2]}); };
  // The corners after the smallest one, orientation kept.
  auto rotation = [](const Triangle& t) {
    const std::size_t at = std::min_element(t.begin(), t.end()) - t.begin();
    return std::pair{t[(at + 1) % 3], t[(at + 2) % 3]};
  };
  for (std::size_t f = 0; f < l.cut.tris.size(); ++f) {
    const Triangle& t = l.cut.tris[f];
    const Triangle& input = mesh.triangles[l.cut.tri_origin[f]];
    for (int i = 0; i < 3; ++i) ASSERT_EQ(l.cut.pos[t[i]], mesh.positions[input[i]]) << f;
    if (f > 0) ASSERT_LE(smallest(l.cut.tris[f - 1]), smallest(t)) << f;
    if (f > 0 && smallest(l.cut.tris[f - 1]) == smallest(t))  // by rotation, no doublets
      ASSERT_LT(rotation(l.cut.tris[f - 1]), rotation(t)) << f;
  }
}

TEST(ClusteringLevel0, SoupMergesIntoTheWeldedBunny) {
  const TriangleMesh mesh = bunny();
  const Level0 welded = level0(mesh), merged = level0(test::as_soup(mesh, true));
  expect_same_level(merged.cut, welded.cut, false);
}

TEST(ClusteringLevel0, DoubletsAndCollapsedTrianglesFollowTheFaceRules) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {5, 5, 5}};
  m.triangles = {{0, 1, 2}, {2, 0, 1}, {0, 3, 1}, {0, 2, 1}};  // a doublet, a line (0-1)
  const Level0 l = level0(m);
  EXPECT_EQ(l.cut.size(), 3u);  // (1, 0, 0) twice is one vertex; (5, 5, 5) is unused
  // Both in the run of their smallest corner, ordered by rotation.
  EXPECT_EQ(std::set<std::uint32_t>(l.cut.tri_origin.begin(), l.cut.tri_origin.end()),
            (std::set<std::uint32_t>{0, 3}));
  EXPECT_TRUE(l.cut.lines.empty());  // (0, 1) is an edge of a kept triangle
}

TEST(ClusteringLevel0, DoesNotDependOnTheThreadCount) {
  const TriangleMesh mesh = test::as_soup(bunny(), true);
  const Level0 parallel = level0(mesh);
  tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
  const Level0 serial = level0(mesh);
  expect_same_level(serial.cut, parallel.cut, true);
}

TEST(ClusteringLevel0, BadInputNamesTheFirstOffender) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}, {0, 1, 7}, {0, 9, 2}};
  EXPECT_THROW(
      {
        try {
          level0(m);
        } catch (const DataError& e) {
          EXPECT_STREQ(e.what(), "vertex clustering: triangle 1 uses vertex 7 of only 3");
          throw;
        }
      },
      DataError);
  m.triangles = {{0, 1, 2}};
  m.positions[2].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(level0(m), DataError);
}

}  // namespace
}  // namespace lodforge::detail::clustering
