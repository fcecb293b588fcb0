// Vertex lookup for split edges and faces: the point of a half edge or of a
// face half-line is the edge point of the child holding it, because every
// node's edge point is the crossing of the finest lattice edge below it.
#include "lodforge/mcoctree/cell_mesh.h"

#include <array>

namespace lodforge::detail {
namespace {

std::array<SlotChildren, kSlotCount> make_slot_children() {
  std::array<SlotChildren, kSlotCount> out{};
  for (int s = 0; s < kSlotCount; ++s) {
    int lo = slot_points()[s][0], hi = slot_points()[s][1];
    int d = hi - lo, ax = d == 1 ? 0 : d == 3 ? 1 : 2;
    int c[3] = {lo % 3, (lo / 3) % 3, lo / 9};
    // Per axis: the child coordinates (octant bit, local 0/1) holding the segment.
    int choices[3][2][2];
    int nchoice[3];
    for (int a = 0; a < 3; ++a) {
      if (a == ax) {
        choices[a][0][0] = c[a], choices[a][0][1] = 0, nchoice[a] = 1;
      } else if (c[a] == 0) {
        choices[a][0][0] = 0, choices[a][0][1] = 0, nchoice[a] = 1;
      } else if (c[a] == 2) {
        choices[a][0][0] = 1, choices[a][0][1] = 1, nchoice[a] = 1;
      } else {
        choices[a][0][0] = 0, choices[a][0][1] = 1;
        choices[a][1][0] = 1, choices[a][1][1] = 0, nchoice[a] = 2;
      }
    }
    for (int i = 0; i < nchoice[0]; ++i)
      for (int j = 0; j < nchoice[1]; ++j)
        for (int k = 0; k < nchoice[2]; ++k) {
          const int* pick[3] = {choices[0][i], choices[1][j], choices[2][k]};
          int octant = pick[0][0] | pick[1][0] << 1 | pick[2][0] << 2;
          int b = pick[(ax + 1) % 3][1] | pick[(ax + 2) % 3][1] << 1;
          out[s].c[out[s].count++] = {static_cast<std::uint8_t>(octant),
                                      static_cast<std::uint8_t>(4 * ax + b)};
        }
  }
  return out;
}

}  // namespace

// At load time rather than on first use: slot_vertex is called for every
// slot of every node the build looks at, and a guarded static costs a check
// per call.
const std::array<SlotChildren, kSlotCount> kSlotChildren = make_slot_children();

int node_triangle_count(const McNode& n, std::uint16_t halved, std::uint8_t split) {
  if (halved == 0 && split == 0) return standard_case(corner_signs(n.signs27)).count;
  CellTriangles cell;
  polygonize_cell({.signs27 = n.signs27, .halved = halved, .split = split}, cell);
  return cell.count;
}

}  // namespace lodforge::detail
