#include "lodforge/simplify/detail/clustering_choice.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lodforge::detail::clustering {
namespace {

// A triangle of area 6 in the plane z = 1: its quadric at a point at height
// h above the plane is 6 h^2, zero on the plane; each of the cells of its
// corners gets it, a degenerate triangle adds nothing.
TEST(ClusteringChoice, PlaneQuadricIsAreaTimesSquaredDistance) {
  const std::vector<Vec3> pos = {{0, 0, 1}, {4, 0, 1}, {0, 3, 1}, {8, 0, 1}};
  const std::vector<Triangle> tris = {{0, 1, 2}, {0, 1, 3}};
  const std::vector<Triangle> mapped = {{0, 1, 2}, {0, 1, 2}};
  Buffer<Quadric> quadric(3, Quadric{});
  add_plane_quadrics(pos, tris, mapped, quadric);
  for (const Quadric& q : quadric) {
    EXPECT_NEAR(q(1, 1, 1), 0, 1e-12);
    EXPECT_NEAR(q(-7, 2, 3), 6 * 4, 1e-9);
    EXPECT_NEAR(q(0, 0, 0.5), 6 * 0.25, 1e-12);
  }
}

// The lists of triangles around the cells: entry 4 f + the corner inside
// the cell, or 4 f + 3 when two corners share it; only wanted cells listed.
TEST(ClusteringChoice, CellFacesListTheTrianglesAroundEachWantedCell) {
  const std::vector<Triangle> mapped = {{0, 1, 2}, {1, 1, 2}, {2, 0, 3}};
  const std::vector<char> wanted = {1, 1, 1, 0};
  CellFaces faces;
  faces.build(mapped, wanted);
  auto list = [&](std::uint32_t cell) {
    return std::vector<std::uint32_t>(faces.entry.begin() + faces.start[cell],
                                      faces.entry.begin() + faces.start[cell + 1]);
  };
  EXPECT_EQ(list(0), (std::vector<std::uint32_t>{0, 8 + 1}));
  EXPECT_EQ(list(1), (std::vector<std::uint32_t>{1, 4 + 3}));
  EXPECT_EQ(list(2), (std::vector<std::uint32_t>{2, 4 + 2, 8 + 0}));
  EXPECT_TRUE(list(3).empty());
}

}  // namespace
}  // namespace lodforge::detail::clustering
