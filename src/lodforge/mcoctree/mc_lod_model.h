#pragma once
/// The run-time model of the marching-cube octree: what extraction needs and
/// nothing else, compiled once from the build-time McOctree.
///
/// Extraction at priority N emits every child of an expanded node that is not
/// expanded itself (Kim, ch. 6). Such a "cell" (a node x with parent p) is
/// emitted for N in [p.priority, x.priority) (the root: [0, its priority)),
/// and within that range its triangles change only where a same-level
/// neighbour's expansion splits one of its faces or edges (the split
/// priorities of McNode). So each cell stores its triangles for each interval
/// over which that split state is constant (a split that changes none of its
/// triangles starts no interval), as index triples into one static vertex
/// table, and extraction copies them after a few integer compares, with no
/// floating point: a renderer uploads the vertex table once and an index
/// buffer per level (continuous LOD by index buffer).
///
/// Size: memory_bytes() per full-resolution triangle is the stored
/// triangles (coarser levels and split variants), the vertices (12-byte
/// position, 4-byte normal; coarse levels' placed vertices included,
/// McBuildOptions::place_coarse_vertices), the cells and the intervals
/// (measured figures in docs/RESULTS.md).
///
/// Cells are grouped by their parent's priority (group 0: the root), so the
/// cells priority N can emit are a prefix of the cell array. Vertices are
/// numbered in the order the cells first use them, so a prefix of the groups
/// uses a prefix of the vertex table: the order of the progressive .mco file.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "lodforge/core/math.h"
#include "lodforge/mcoctree/mc_octree.h"
#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

/// One emitted node of the tree.
struct McLodCell {
  /// The priority from which the cell is expanded (its children replace it);
  /// kNever for a node never expanded.
  std::uint32_t until = 0;
  /// Its first interval in McLodModel::intervals; its intervals end at the
  /// next cell's first.
  std::uint32_t first_interval = 0;
  bool operator==(const McLodCell&) const = default;
};

/// A range of priorities over which a cell's split state, so its triangles,
/// are constant: from `from` up to the next interval's `from` (or the cell's
/// `until`).
struct McLodInterval {
  std::uint32_t from = 0;
  /// First triangle in McLodModel::triangles; the interval's triangles end at
  /// the next interval's first.
  std::uint32_t first_triangle = 0;
  bool operator==(const McLodInterval&) const = default;
};

struct McLodModel {
  static constexpr std::uint32_t kNever = std::numeric_limits<std::uint32_t>::max();
  /// Spare triangles after the last real one in `triangles`, so that
  /// extraction may copy a fixed block of kCopyBlock triangles from any
  /// interval start.
  static constexpr std::size_t kCopyBlock = 4;

  int depth = 0;        ///< of the tree it was compiled from
  Vec3 origin;          ///< the root cube's lowest corner
  float cell_size = 0;  ///< edge length of a finest cell
  /// Vertex table: every vertex some level uses (the tree's edge points and
  /// the loop centroids of cell_polygonize.cpp), in order of first use.
  std::vector<Vec3> positions;
  std::vector<std::uint32_t> normals;  ///< #positions, octahedral 2 x 16 bit (encode_normal)
  std::vector<Rgb8> colors;            ///< empty or #positions
  /// group[k] = first cell whose parent has priority k (k = 0: the root),
  /// k = 0 .. L + 1 (L priorities; group[L + 1] = the cell count).
  std::vector<std::uint32_t> group;
  std::vector<McLodCell> cells;  ///< #cells + 1 (a sentinel closing the last cell's intervals)
  std::vector<McLodInterval> intervals;  ///< + 1 sentinel closing the last interval
  std::vector<Triangle> triangles;       ///< + kCopyBlock zero triangles of padding
  /// The accumulation table: accumulated[N] = triangles at priority N, N = 0 .. L.
  std::vector<std::uint64_t> accumulated;
  /// Vertices that are loop centroids, ascending (rare; for statistics).
  std::vector<std::uint32_t> centroids;

  /// Priorities (the LOD array's length).
  std::uint32_t priorities() const {
    return accumulated.empty() ? 0 : static_cast<std::uint32_t>(accumulated.size() - 1);
  }
  std::uint64_t full_triangles() const { return accumulated.empty() ? 0 : accumulated.back(); }
  std::size_t cell_count() const { return cells.empty() ? 0 : cells.size() - 1; }
  /// Triangles stored over all cells and intervals (without the padding).
  std::size_t stored_triangles() const {
    return triangles.size() < kCopyBlock ? 0 : triangles.size() - kCopyBlock;
  }
  /// Bytes of all arrays (their sizes, not capacities): the run-time memory.
  std::size_t memory_bytes() const;
};

/// Compiles the run-time model of `tree`: triangulates every cell once per
/// interval of constant split state (integer work, plus the float average
/// of a loop centroid, rare). O(cells x intervals); the tree may be dropped
/// afterwards.
McLodModel compile_mc_lod(const McOctree& tree);

/// Octahedral normal encoding (Cigolle et al., "A survey of efficient
/// representations for independent unit vectors", JCGT 2014): u in the low,
/// v in the high 16 bits, each a signed normalised integer. Angular error
/// below 0.05 degrees.
std::uint32_t encode_normal(Vec3 n);
/// The unit vector of encode_normal's code.
inline Vec3 decode_normal(std::uint32_t code) {
  float u = static_cast<float>(static_cast<std::int16_t>(code & 0xffffu)) / 32767.0f;
  float v = static_cast<float>(static_cast<std::int16_t>(code >> 16)) / 32767.0f;
  Vec3 n{u, v, 1.0f - std::abs(u) - std::abs(v)};
  if (n.z < 0) {
    float x = (1.0f - std::abs(v)) * (u >= 0 ? 1.0f : -1.0f);
    float y = (1.0f - std::abs(u)) * (v >= 0 ? 1.0f : -1.0f);
    n.x = x, n.y = y;
  }
  return normalized(n);
}

}  // namespace lodforge
