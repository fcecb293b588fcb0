#pragma once
/// The marching-cube octree: the build-time model `build_mc_octree` makes and
/// `compile_mc_lod` turns into the run-time model (mc_lod_model.h) that
/// extraction reads and `write_mco_file` / `read_mco_file` store.
///
/// A node is a marching cube: the signs of its corners (and of the points of
/// its 3x3x3 half-spacing lattice, which its children's corners give) and, on
/// each of its 12 edges, the surface point (an index into the vertex table, the
/// crossing of the finest lattice edge that holds it: the thesis's edge ratio
/// re-scaled level by level, Fig. 5.2). Empty nodes (no crossing anywhere in
/// them) are not stored.
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "lodforge/core/math.h"

namespace lodforge {

struct McNode {
  static constexpr std::uint32_t kNone = lodforge::kNone;
  /// Index of the first child; the children present (bit o of child_mask,
  /// octant o = x + 2y + 4z) follow one another in octant order. kNone for a leaf.
  std::uint32_t first_child = kNone;
  std::uint8_t child_mask = 0;
  std::uint8_t level = 0;  ///< 0 = root; depth = finest
  std::uint16_t pad = 0;
  /// Bit p (p = i + 3j + 9k, i,j,k in 0..2 at half the node's size) set: the
  /// lattice point is inside. Leaves carry only their 8 corners.
  std::uint32_t signs27 = 0;
  std::array<std::uint32_t, 3> coords{};  ///< cell coordinates at this level
  /// Edge e = 4a + b (see cell_polygonize.h): its surface point, or kNone.
  std::array<std::uint32_t, 12> edge_vertex;
  /// Position in the LOD array (1-based); kNone for a node never expanded (a leaf).
  std::uint32_t priority = kNone;
  /// Smallest priority at which face f / edge e of this node is split by an
  /// expanded neighbour of the same level (kNone: never). Precomputed so that
  /// extraction only compares integers.
  std::array<std::uint32_t, 6> face_split{};
  std::array<std::uint32_t, 12> edge_split{};

  McNode() { edge_vertex.fill(kNone); }
  bool leaf() const { return child_mask == 0; }
  /// Index of the child in octant o, or kNone.
  std::uint32_t child(int o) const {
    if (!(child_mask >> o & 1)) return kNone;
    return first_child + kBitCount[child_mask & ((1u << o) - 1)];
  }

 private:
  // Set bits of each byte: __builtin_popcount is a library call on the
  // baseline x86-64 (no POPCNT), and child() is in every inner loop.
  static constexpr std::array<std::uint8_t, 256> kBitCount = [] {
    std::array<std::uint8_t, 256> n{};
    for (int b = 1; b < 256; ++b) n[b] = static_cast<std::uint8_t>(n[b >> 1] + (b & 1));
    return n;
  }();
};

/// A packed RGB colour.
using Rgb8 = std::array<std::uint8_t, 3>;

struct McOctree {
  int depth = 0;                ///< levels below the root; 2^depth finest cells per axis
  Vec3 origin;                  ///< the root cube's lowest corner
  float cell_size = 0;          ///< edge length of a finest cell
  std::vector<Vec3> positions;  ///< vertex table: the surface points
  std::vector<Vec3> normals;    ///< #positions, unit
  std::vector<Rgb8> colors;     ///< empty or #positions
  std::vector<McNode> nodes;    ///< [0] = root; level by level, Morton order within a level
  /// The LOD array: lod[i - 1] = the node of priority i (the i-th to expand).
  std::vector<std::uint32_t> lod;
  /// The accumulation table: accumulated[N] = triangles extracted at priority N
  /// (N = 0: the root alone), N = 0 .. lod.size().
  std::vector<std::uint64_t> accumulated;
  /// Triangles of the full-resolution mesh (accumulated.back()).
  std::uint64_t full_triangles() const { return accumulated.empty() ? 0 : accumulated.back(); }
  std::size_t memory_bytes() const;
};

}  // namespace lodforge
