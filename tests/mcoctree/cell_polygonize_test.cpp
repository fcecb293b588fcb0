#include "lodforge/mcoctree/cell_polygonize.h"

#include <gtest/gtest.h>

#include <map>
#include <utility>

namespace lodforge::detail {
namespace {

// Every loop slot is used by exactly one triangle edge in each direction
// inside the cell, except boundary segments which appear once: so counting
// directed edges, each undirected edge between slots appears once (boundary)
// or twice in opposite directions (interior diagonal).
void check_cell(const CellConfig& config) {
  CellTriangles out;
  polygonize_cell(config, out);
  std::map<std::pair<int, int>, int> directed;
  for (int i = 0; i < out.count; ++i)
    for (int k = 0; k < 3; ++k) {
      int a = out.triangles[i][k], b = out.triangles[i][(k + 1) % 3];
      ASSERT_NE(a, b);
      ++directed[{a, b}];
    }
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1) << "edge used twice in one direction";
    bool interior = directed.count({e.second, e.first}) > 0;
    if (!interior) {
      // A boundary segment lies in one face of the cell.
      if (e.first < kSlotCount && e.second < kSlotCount)
        EXPECT_NE(slot_faces()[e.first] & slot_faces()[e.second], 0) << e.first << " " << e.second;
    } else if (e.first < kSlotCount && e.second < kSlotCount) {
      EXPECT_EQ(slot_faces()[e.first] & slot_faces()[e.second], 0) << "diagonal within a face";
    }
  }
}

TEST(CellPolygonize, AllStandardCasesAreClosedFans) {
  for (int c = 0; c < 256; ++c) {
    std::uint32_t signs = 0;
    for (int k = 0; k < 8; ++k)
      if (c >> k & 1) signs |= 1u << corner_point(k);
    check_cell({.signs27 = signs});
    const StandardCase& sc = standard_case(static_cast<std::uint8_t>(c));
    if (c == 0 || c == 255) EXPECT_EQ(sc.count, 0);
    // The inside is always separated on ambiguous faces, so a configuration
    // and its complement may differ (case 2 inside corners on one face: 2
    // triangles; their complement joins them: 4).
  }
  EXPECT_EQ(standard_case(1).count, 1);
  EXPECT_EQ(standard_case(3).count, 2);
}

TEST(CellPolygonize, OneCornerTriangleFacesAwayFromIt) {
  // Corner 0 inside: triangle on edges 0 (x), 4 (y), 8 (z), CCW seen from (1,1,1).
  const StandardCase& sc = standard_case(1);
  ASSERT_EQ(sc.count, 1);
  std::array<int, 3> e = {sc.edges[0][0], sc.edges[0][1], sc.edges[0][2]};
  while (e[0] != 0) std::rotate(e.begin(), e.begin() + 1, e.end());
  EXPECT_EQ(e[1], 4);
  EXPECT_EQ(e[2], 8);
}

TEST(CellPolygonize, RandomSplitConfigurations) {
  std::uint64_t state = 12345;
  auto next = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<std::uint32_t>(state >> 33);
  };
  for (int iter = 0; iter < 20000; ++iter) {
    std::uint8_t split = static_cast<std::uint8_t>(next() & 63 & next());
    std::uint16_t halved = static_cast<std::uint16_t>(next() & 0xfff & next());
    for (int f = 0; f < 6; ++f)
      if (split >> f & 1)
        for (int e = 0; e < 12; ++e)
          if (edge_faces(e) >> f & 1) halved |= static_cast<std::uint16_t>(1u << e);
    check_cell({.signs27 = next() & 0x7ffffff, .halved = halved, .split = split});
  }
}

}  // namespace
}  // namespace lodforge::detail
