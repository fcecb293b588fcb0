#pragma once
/// From a node of the marching-cube octree and the split state of its
/// neighbours to its triangles (detail of build and extraction).
#include <array>
#include <cstdint>

#include "lodforge/mcoctree/cell_polygonize.h"
#include "lodforge/mcoctree/mc_octree.h"

namespace lodforge::detail {

/// Per slot, the children's edges that may hold its point: (octant, edge of
/// that child), the first present child's (a half edge has one candidate, a
/// face half-line two).
struct SlotChildren {
  struct Candidate {
    std::uint8_t octant;
    std::uint8_t edge;
  };
  std::array<Candidate, 2> c{};
  int count = 0;
};
extern const std::array<SlotChildren, kSlotCount> kSlotChildren;

/// The vertex of `slot` (< kSlotCount) of node `n` when the edges in `halved`
/// are split: a whole edge's point, or the point of the child holding the half
/// or face half-line (kNone if there is none). Inline: the build asks it for
/// every slot of every node.
inline std::uint32_t slot_vertex(const McOctree& tree, const McNode& n, int slot,
                                 std::uint16_t halved) {
  if (slot < 24 && !(halved >> (slot / 2) & 1)) return n.edge_vertex[slot / 2];
  const SlotChildren& sc = kSlotChildren[slot];
  for (int i = 0; i < sc.count; ++i) {
    std::uint32_t c = n.child(sc.c[i].octant);
    if (c != McNode::kNone) return tree.nodes[c].edge_vertex[sc.c[i].edge];
  }
  return McNode::kNone;
}

/// Triangulates node `n` as a cell of the extracted surface; calls
/// emit(a, b, c) with vertex indices (kNone never appears) and, for a loop
/// that needs a centroid, centroid(slots, count, halved) -> vertex index first.
/// Returns the number of triangles.
template <class Emit, class Centroid>
int triangulate_node(const McOctree& tree, const McNode& n, std::uint16_t halved,
                     std::uint8_t split, Emit&& emit, Centroid&& centroid) {
  if (halved == 0 && split == 0) {
    const StandardCase& sc = standard_case(corner_signs(n.signs27));
    for (int i = 0; i < sc.count; ++i)
      emit(n.edge_vertex[sc.edges[i][0]], n.edge_vertex[sc.edges[i][1]],
           n.edge_vertex[sc.edges[i][2]]);
    return sc.count;
  }
  CellTriangles cell;
  polygonize_cell({.signs27 = n.signs27, .halved = halved, .split = split}, cell);
  std::uint32_t centre[kMaxFallbackLoops];
  for (int f = 0; f < cell.fallback_count; ++f)
    centre[f] = centroid(cell.fallback_loops[f].data(), cell.fallback_sizes[f], halved);
  auto vertex = [&](std::uint8_t s) {
    return s >= kFallbackSlot ? centre[s - kFallbackSlot] : slot_vertex(tree, n, s, halved);
  };
  for (int i = 0; i < cell.count; ++i)
    emit(vertex(cell.triangles[i][0]), vertex(cell.triangles[i][1]), vertex(cell.triangles[i][2]));
  return cell.count;
}

/// Triangle count of node `n` as a cell (no vertex lookups).
int node_triangle_count(const McNode& n, std::uint16_t halved, std::uint8_t split);

}  // namespace lodforge::detail
