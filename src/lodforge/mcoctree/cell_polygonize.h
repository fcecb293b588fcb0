#pragma once
/// Triangulation of one marching cube whose faces and edges may be split where
/// a finer neighbour touches them (detail of the marching-cube octree).
///
/// The cell is seen at half spacing: a 3x3x3 lattice of points (i,j,k) in
/// {0,1,2}^3, index i + 3j + 9k; the cell's corners are the even points, corner
/// c = x + 2y + 4z sits at lattice point 2x + 6y + 18z. Edge e = 4a + b runs
/// along axis a at coordinate 2*(b&1) on axis (a+1)%3 and 2*(b>>1) on axis
/// (a+2)%3. Face f = 2a + s is the face at coordinate 2s on axis a.
///
/// A "slot" names the place of a vertex on the cell boundary:
///   2e + h       the half h of edge e (h = 0: the half at the lower end);
///                a whole (unsplit) edge uses slot 2e for its one crossing
///   24 + 4f + k  the half-line k of face f from its centre to the middle of a
///                side (k = 0: towards u = 0, 1: u = 2, 2: v = 0, 3: v = 2, with
///                u = axis (a+1)%3, v = axis (a+2)%3)
/// Slots >= kFallbackSlot name an extra vertex at the centroid of a boundary
/// loop no diagonal of which may be drawn (see cell_polygonize.cpp).
#include <array>
#include <cstdint>

namespace lodforge::detail {

inline constexpr int kSlotCount = 48;
inline constexpr std::uint8_t kFallbackSlot = 64;
inline constexpr int kMaxCellTriangles = 96;
inline constexpr int kMaxFallbackLoops = 8;

/// What a cell is triangulated from. signs27 bit p: lattice point p is inside.
/// Only the points the split faces and halved edges use are read (for a cell
/// with nothing split, only the 8 corners). Precondition: a split face's four
/// edges are halved.
struct CellConfig {
  std::uint32_t signs27 = 0;
  std::uint16_t halved = 0;  ///< bit e: edge e is split at its middle
  std::uint8_t split = 0;    ///< bit f: face f is split 2x2
};

struct CellTriangles {
  std::array<std::array<std::uint8_t, 3>, kMaxCellTriangles>
      triangles{};  ///< slots, CCW seen from outside
  int count = 0;
  /// The loops whose centroid is slot kFallbackSlot + i: their slots, in order.
  std::array<std::array<std::uint8_t, kSlotCount>, kMaxFallbackLoops> fallback_loops{};
  std::array<std::uint8_t, kMaxFallbackLoops> fallback_sizes{};
  int fallback_count = 0;
};

/// Triangulates the surface through the cell: the contour of each face (each
/// split face as four quarters) from the signs, inside corners cut off by the
/// segments ("separate the inside"), the contours joined into loops over the
/// cell boundary and each loop triangulated without a diagonal joining two
/// vertices of one face. Integer work only.
void polygonize_cell(const CellConfig& config, CellTriangles& out);

/// Triangle count of the cell with nothing split, by corner signs (bit c =
/// corner c inside), and those triangles as edge numbers: a table built once.
struct StandardCase {
  std::uint8_t count = 0;
  std::array<std::array<std::uint8_t, 3>, 12> edges{};  ///< edge numbers, CCW seen from outside
};
const StandardCase& standard_case(std::uint8_t corner_signs);

/// Lattice point index of corner c.
constexpr int corner_point(int c) {
  return 2 * (c & 1) + 6 * ((c >> 1) & 1) + 18 * (c >> 2);
}
/// The corner signs (bit c) of a 27-point sign mask.
std::uint8_t corner_signs(std::uint32_t signs27);
/// The 27-point index of a lattice point.
constexpr int lattice_point(int i, int j, int k) {
  return i + 3 * j + 9 * k;
}
/// The two lattice points (i,j,k) of each slot's segment, first the lower.
const std::array<std::array<std::uint8_t, 2>, kSlotCount>& slot_points();
/// Bit f set for each face f the slot's segment lies in.
const std::array<std::uint8_t, kSlotCount>& slot_faces();
/// The faces (bit f) that contain edge e.
std::uint8_t edge_faces(int e);
/// The corners (lower, upper) of edge e.
std::array<int, 2> edge_corners(int e);

}  // namespace lodforge::detail
