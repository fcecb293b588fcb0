#pragma once
/// Out-of-core vertex clustering (Lindstrom, "Out-of-Core Simplification of
/// Large Polygonal Models", SIGGRAPH 2000): simplifies a mesh file larger
/// than memory, reading its triangles as a stream (mesh/triangle_stream.h);
/// memory grows with the output, not the input.
///
/// Space is cut into a uniform grid of cubic cells over the bounding box of
/// the triangles. One pass over the triangles adds each triangle's
/// area-weighted plane quadric (Garland & Heckbert 1997) to the cells of its
/// three corners, and keeps each triangle whose corners fall in three
/// distinct cells as a cell triple (the same triple again, in the same
/// orientation, is kept once). Each cell that is a corner of a kept triple
/// becomes one vertex, placed at the minimum of its quadric regularised
/// towards the mean of the corners that fell in it (core/quadric.h
/// quadric_minimum, the rule of simplify/vertex_clustering.h) and clamped
/// into the cell. Triangles that collapse to a line or a point vanish (no
/// line segments); the output has no attributes.
///
/// How the grid is chosen (cell side h; the grid covers the bounding box,
/// at most 2^21 cells a side):
///
/// | options                     | h                                                       |
/// |-----------------------------|---------------------------------------------------------|
/// | grid = n > 0                | longest box side / n (one clustering pass)              |
/// | a triangle count T          | first sqrt(3 A / T), A the input's surface area: a      |
/// |                             | plane crosses 1.5 cells per h^2 of area on average over |
/// |                             | orientations, and a closed surface has 2 triangles per  |
/// |                             | vertex; then, while the result has more than T          |
/// |                             | triangles or fewer than 0.7 T, h x sqrt(result / T),    |
/// |                             | keeping the largest result <= T (at most 6 passes)      |
/// | max_error E                 | h <= E / sqrt(3) (cell diagonal <= E), finest wins      |
/// | neither                     | the finest grid (2^21 a side): equal positions merge    |
///
/// A clustering pass that reaches 4 T + 65 536 triangles stops early and the
/// pass is run again with 2 h, so a bad first estimate (a surface much
/// rougher than its area says) cannot take memory beyond a few times the
/// output's (unless the error budget forbids 2 h: then the pass runs whole). Before the passes, one
/// survey pass over the triangles finds the bounding box, the area and the triangle count.
///
/// `error`, in model units, is an upper bound on the displacement of an
/// input vertex: the largest distance from a cell's representative to the
/// farthest corner of the bounding box of the input corners in the cell,
/// over the output's cells. It is at most the cell diagonal sqrt(3) h. It is
/// NOT a bound on the surface deviation (Hausdorff distance): measure that
/// with `lodforge compare` (metrics/compare_meshes.h) on the result and the
/// input, which needs both in memory.
///
/// Result: `mesh` (positions and triangles, vertices in Morton order of
/// their cells, triangles sorted by their corners), `vertex_map` (per
/// vertex, the smallest input vertex index in its cell: PLY the vertex, STL
/// 3 x triangle + corner; 2^32 - 1 beyond 32 bits), `face_map` (per
/// triangle, the first input triangle, in stream order, that gave its
/// triple), `error` (above), `stop_reason` (kTargetReached; kErrorBudgetReached
/// when the error budget keeps the cells finer than the count asks;
/// kCannotSimplify when the passes end above the count, or the input has no
/// triangle; kNoReduction without a count or error), `stop_detail` (grid,
/// cell side, passes).
///
/// Time: O(F) per pass (a pass reads the file once; hash maps of the cells
/// and the triples). Memory: O(output cells + output triangles), about 150
/// bytes a cell and 30 a triangle, plus the stream's chunks. Single-threaded
/// passes over chunks whose triangles are prepared in parallel (TBB); the
/// result does not depend on the thread count or the chunk size. Throws what
/// the stream throws (DataError for bad or truncated files).
#include <cstddef>
#include <cstdint>

#include "lodforge/mesh/triangle_stream.h"
#include "lodforge/simplify/simplify_result.h"

namespace lodforge {

struct OutOfCoreClusteringOptions {
  /// Triangle count or ratio of the input's triangles, and/or max_error, a
  /// bound on `error` (see the table above).
  SimplifyTarget target;
  /// Cells along the longest side of the bounding box (0: from the target).
  std::uint32_t grid = 0;
};

/// What out_of_core_clustering returns: the result every simplifier returns,
/// and what the passes saw.
struct OutOfCoreClusteringResult : SimplifyResult {
  std::uint64_t input_triangles = 0;  ///< triangles of the input, after fan triangulation
  int passes = 0;                     ///< passes over the input, the survey included
};

/// Clusters the triangles of `input` into a simplified mesh (see above).
OutOfCoreClusteringResult out_of_core_clustering(const TriangleStream& input,
                                                 const OutOfCoreClusteringOptions& options = {});

}  // namespace lodforge
