#include "lodforge/simplify/detail/clustering_faces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

namespace lodforge::detail::clustering {
namespace {

struct Remapped {
  Cut to;
  RemapScratch scratch;
  Buffer<Segment> candidates;
};

/// Triangles already mapped to 6 new vertices (vertex 5 used by none), and
/// lines of a previous level of 7 vertices (5 -> 1, 6 -> 3).
Remapped remap_example(bool no_lines) {
  const std::vector<Triangle> mapped = {
      {0, 1, 2},  // kept
      {1, 2, 0},  // the same rotation: a doublet, dropped
      {0, 2, 1},  // the other orientation: kept
      {0, 0, 3},  // collapses to the line (0, 3)
      {2, 2, 2},  // collapses to a point: dropped
      {1, 3, 4},  // kept
      {3, 4, 4},  // collapses to (3, 4), an edge of the one before: dropped
  };
  const std::vector<std::uint32_t> origin = {10, 11, 12, 13, 14, 15, 16};
  const std::vector<Segment> lines = {{0, 6}, {2, 6}, {5, 5}};
  const std::vector<std::uint32_t> vertex_map = {0, 1, 2, 3, 4, 1, 3};
  Remapped r;
  remap_faces(mapped, origin, lines, vertex_map, 6, no_lines, r.candidates, r.to, r.scratch);
  return r;
}

TEST(ClusteringFaces, RemapAppliesTheFaceRules) {
  const Remapped r = remap_example(false);
  EXPECT_EQ(std::vector<Triangle>(r.to.tris.begin(), r.to.tris.end()),
            (std::vector<Triangle>{{0, 1, 2}, {0, 2, 1}, {1, 3, 4}}));
  EXPECT_EQ(std::vector<std::uint32_t>(r.to.tri_origin.begin(), r.to.tri_origin.end()),
            (std::vector<std::uint32_t>{10, 12, 15}));
  // (0, 3) from the collapsed triangle; the line (0, 6) maps onto it again;
  // (2, 6) maps to the new line (2, 3); (5, 5) to a point.
  EXPECT_EQ(std::vector<Segment>(r.to.lines.begin(), r.to.lines.end()),
            (std::vector<Segment>{{0, 3}, {2, 3}}));
}

TEST(ClusteringFaces, NoLinesDropsCollapsedTrianglesButKeepsLines) {
  const Remapped r = remap_example(true);
  EXPECT_EQ(r.to.tris.size(), 3u);
  EXPECT_EQ(std::vector<Segment>(r.to.lines.begin(), r.to.lines.end()),
            (std::vector<Segment>{{0, 3}, {2, 3}}));
}

TEST(ClusteringFaces, UnusedVerticesAreDroppedInOrder) {
  Remapped r = remap_example(false);
  r.to.pos = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {4, 0, 0}, {5, 0, 0}};
  const std::size_t kept = number_used_vertices(6, r.to, r.scratch);
  EXPECT_EQ(kept, 5u);  // vertex 5: no face uses it
  compact_vertices(6, kept, r.to, r.scratch);
  ASSERT_EQ(r.to.pos.size(), 5u);
  EXPECT_EQ(r.to.pos[4], (Vec3{4, 0, 0}));
  EXPECT_EQ(r.scratch.keep[5], kNone);
}

// Runs of every length up to 40 with random rotations, orientations and
// doublets: the result is the run sorted stably by canonical rotation with
// the first of each equal rotation kept.
TEST(ClusteringFaces, DedupeRunKeepsTheFirstOfEachRotationInOrder) {
  std::mt19937 random(7);
  RemapScratch scratch;
  for (std::size_t n = 1; n <= 40; ++n) {
    std::vector<Triangle> tris;
    std::vector<std::uint32_t> origin;
    for (std::size_t i = 0; i < n; ++i) {
      std::uint32_t b = 1 + random() % 4, c = 1 + random() % 4;
      if (b == c) c = b + 1;
      const Triangle canonical{0, b, c};
      const std::size_t rotation = random() % 3;
      tris.push_back(
          {canonical[rotation], canonical[(rotation + 1) % 3], canonical[(rotation + 2) % 3]});
      origin.push_back(static_cast<std::uint32_t>(i));
    }
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> first;  // sorted, first kept
    for (std::size_t i = 0; i < n; ++i) {
      const Triangle& t = tris[i];
      const std::size_t at = std::find(t.begin(), t.end(), 0u) - t.begin();
      first.emplace(std::pair{t[(at + 1) % 3], t[(at + 2) % 3]}, origin[i]);
    }
    const std::size_t kept = dedupe_run(tris.data(), origin.data(), n, 0, scratch);
    ASSERT_EQ(kept, first.size()) << n;
    std::size_t i = 0;
    for (const auto& [key, o] : first) {
      EXPECT_EQ(origin[i], o) << n;
      const Triangle& t = tris[i];
      const std::size_t at = std::find(t.begin(), t.end(), 0u) - t.begin();
      EXPECT_EQ((std::pair{t[(at + 1) % 3], t[(at + 2) % 3]}), key) << n;
      ++i;
    }
  }
}

}  // namespace
}  // namespace lodforge::detail::clustering
