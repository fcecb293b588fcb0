#pragma once
/// The finest lattice of the marching-cube octree and its corner signs, as
/// the sign sources (mesh_signs.h, scan_signs.h) fill it and the tree
/// builder (octree_builder.h) reads it (detail of build_mc_octree).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "lodforge/core/math.h"

namespace lodforge::detail {

/// Bits of Lattice::state. kInside: the point is inside; kExact: it has an
/// exact signed distance; kAssigned: its sign is decided; kMeasured: a point
/// nearest an open rim, measured without a sign.
inline constexpr std::uint8_t kInside = 1, kExact = 2, kAssigned = 4, kMeasured = 8;

/// The finest lattice: the points of the root cube (2^depth cells a side,
/// centred on the input's box) that the box, grown by a cell, spans (beyond
/// it everything is empty), a sign for each, an exact signed distance for the
/// band. Lattice point (i, j, k) is root-cube point (i, j, k) + offset.
struct Lattice {
  int depth = 0;
  std::array<std::int64_t, 3> dim{};     // points per axis
  std::array<std::int64_t, 3> offset{};  // of the first point, in cells of the root cube
  Vec3 root;                             // the root cube's lowest corner
  Vec3 origin;
  float h = 0;
  std::vector<std::uint8_t> state;
  struct Exact {
    std::int64_t idx;
    float distance;          // signed
    std::uint32_t triangle;  // the closest one (meshes), else kNone
    bool operator<(const Exact& o) const { return idx < o.idx; }
  };
  std::vector<Exact> distance;  // exact ones, sorted by index at the end

  const Exact* find_distance(std::int64_t idx) const {
    auto it = std::lower_bound(distance.begin(), distance.end(), Exact{idx, 0, 0});
    return it != distance.end() && it->idx == idx ? &*it : nullptr;
  }

  std::int64_t index(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return i + dim[0] * (j + dim[1] * k);
  }
  std::int64_t plane() const { return dim[0] * dim[1]; }
  std::array<std::int64_t, 3> coords(std::int64_t idx) const {
    return {idx % dim[0], (idx / dim[0]) % dim[1], idx / plane()};
  }
  Vec3 point(std::int64_t idx) const {
    auto c = coords(idx);
    return root + Vec3{static_cast<float>(c[0] + offset[0]), static_cast<float>(c[1] + offset[1]),
                       static_cast<float>(c[2] + offset[2])} *
                      h;
  }
  bool inside(std::int64_t idx) const { return state[idx] & kInside; }
  /// Calls fn(edge, x, y, z) for each cell of the lattice around the crossed
  /// lattice edge `key` (point * 3 + axis a): it is edge 4a + q of the cell
  /// whose lower corner is q's offsets (bit 0 on axis a + 1, bit 1 on a + 2)
  /// below it; x, y, z in root-cube cell coordinates.
  template <class Fn>
  void for_each_cell_around(std::int64_t key, Fn&& fn) const {
    const std::int64_t p = key / 3, a = key % 3;
    const auto c = coords(p);
    const int a1 = static_cast<int>((a + 1) % 3), a2 = static_cast<int>((a + 2) % 3);
    for (int q = 0; q < 4; ++q) {
      std::int64_t cell[3] = {c[0], c[1], c[2]};
      cell[a1] -= q & 1, cell[a2] -= q >> 1;
      if (cell[a1] < 0 || cell[a2] < 0 || cell[a1] + 1 >= dim[a1] || cell[a2] + 1 >= dim[a2])
        continue;
      fn(static_cast<int>(4 * a + q), cell[0] + offset[0], cell[1] + offset[1],
         cell[2] + offset[2]);
    }
  }
  bool on_border(std::int64_t idx) const {
    auto c = coords(idx);
    for (int a = 0; a < 3; ++a)
      if (c[a] == 0 || c[a] == dim[a] - 1) return true;
    return false;
  }
};

/// An empty lattice whose root cube (the next power of two above
/// resolution + 2 cells a side, centred on `box`) holds `box` with a cell to
/// spare on every side; cells are the longest side of `box` / resolution.
/// Throws DataError when `box` is a single point. Precondition: resolution >= 1.
Lattice empty_lattice(const Box3& box, int resolution);

/// Calls fn(q) for each of the (up to 6) lattice points next to `idx`.
template <class Fn>
void lattice_neighbours(const Lattice& lat, std::int64_t idx, Fn&& fn) {
  const std::int64_t step[3] = {1, lat.dim[0], lat.plane()};
  auto c = lat.coords(idx);
  for (int a = 0; a < 3; ++a) {
    if (c[a] > 0) fn(idx - step[a]);
    if (c[a] + 1 < lat.dim[a]) fn(idx + step[a]);
  }
}

/// Runs fn(k, out) for the layers k in [first, last) of the lattice in
/// parallel, each appending to its own vector, and returns what they appended
/// in layer order (what one loop over the layers would give).
template <class Fn>
std::vector<std::int64_t> collect_by_layer(std::int64_t first, std::int64_t last, Fn&& fn) {
  std::vector<std::vector<std::int64_t>> part(
      static_cast<std::size_t>(std::max<std::int64_t>(last - first, 0)));
  tbb::parallel_for(first, last,
                    [&](std::int64_t k) { fn(k, part[static_cast<std::size_t>(k - first)]); });
  std::size_t n = 0;
  for (const auto& p : part) n += p.size();
  std::vector<std::int64_t> out;
  out.reserve(n);
  for (const auto& p : part) out.insert(out.end(), p.begin(), p.end());
  return out;
}

}  // namespace lodforge::detail
