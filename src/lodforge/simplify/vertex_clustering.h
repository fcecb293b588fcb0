#pragma once
/// Vertex clustering by octree quantisation (the LODCreator thesis): the
/// whole chain of levels of detail of a triangle mesh or line set in one pass.
///
/// The used vertices are inserted into an octree over the cube that bounds
/// them (one distinct coordinate per leaf; equal coordinates merge). A level
/// is made by merging the deepest leaves into their parents, again and again,
/// until the vertex count has dropped by at least `min_diff` relative to the
/// previous level; every merged cell keeps one representative, chosen among
/// the previous level's vertices in the cell by the weighted heuristics below.
/// Triangles are then remapped onto the representatives: doublets (the same
/// triangle again, same orientation) are dropped, triangles that collapse to a
/// line become line segments (`TriangleMesh::lines`) unless `no_lines`, and
/// triangles that collapse to a point vanish; a line equal to another line or
/// to an edge of a kept triangle is dropped. Because the octree cuts space,
/// not the surface, this works on any input: triangle soup, non-manifold
/// edges and vertices, T-junctions, degenerate triangles, several components.
///
/// Representative choice, per merged cell with vertices (candidates) x_i; each
/// heuristic's values are divided by their largest value over the cell's
/// candidates (so each lies in [0, 1]) before weighting, and the candidate
/// with the smallest weighted sum wins (ties: the first in octree order).
/// With the quadric heuristic on, a candidate whose weighted quadric term
/// exceeds the smallest one by more than the sum of the other weights cannot
/// win; area and volume are computed, and normalised, over the candidates
/// left (the contenders) only, and a cell with one contender takes it:
///
/// | heuristic     | value for candidate x                                      | weight |
/// |---------------|------------------------------------------------------------|--------|
/// | error area    | abs(sum_f area(f, its corners in the cell moved to x)      | 8      |
/// |               |     - sum_f area(f))                                       |        |
/// | error volume  | sum_f abs(volume of the tetrahedron (f, x))                | 1      |
/// | weighted mean | distance from x to the mean of the cell's vertices, each   | 0      |
/// |               | weighted by the input coordinates it stands for            |        |
/// | quadric       | Q(x), Q = sum of the area-weighted plane quadrics of the   | 32     |
/// |               | input triangles around the cell's input vertices           |        |
///
/// f runs over the triangles of the previous level that use a vertex of the
/// cell. A cell whose vertices have no triangle (a line set, or lines of a
/// mixed mesh) uses the weighted mean alone. The quadric heuristic is not in
/// the thesis: it is Lindstrom's representative ("Out-of-core simplification
/// of large polygonal models", SIGGRAPH 2000). When `quadric_weight > 0` the
/// quadric-optimal point of the cell (the minimum of Q, regularised towards
/// the weighted mean where Q is flat, clamped to the cell) is one more
/// candidate, scored by all four heuristics like the others; it gets the
/// attributes and the vertex_map entry of the nearest vertex of the cell.
///
/// Why the default quadric weight 32: with the thesis' heuristics alone
/// (`quadric_weight = 0`, the thesis' method exactly) the results miss the
/// thesis' own published deviations; with weight 32 the quadric point wins
/// most cells while the area and volume terms still vote, within a few
/// percent of the quadric alone (figures in docs/RESULTS.md).
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/simplify/simplify_result.h"

namespace lodforge {

struct VertexClusteringOptions {
  float area_weight = 8;      ///< error area heuristic (thesis default 8)
  float volume_weight = 1;    ///< error volume heuristic (thesis default 1)
  float mean_weight = 0;      ///< weighted mean heuristic (thesis default 0)
  float quadric_weight = 32;  ///< Lindstrom's quadric heuristic (0: the thesis' method)
  /// Each level has at most (1 - min_diff) x the previous level's vertices
  /// (0.2 = the thesis' 20 %); clamped to [0, 1]. 0 still asks for at least
  /// one vertex fewer. 1 gives level 0 alone.
  float min_diff = 0.2f;
  /// Drop triangles that collapse to a line instead of keeping them as line
  /// segments. Line segments of the input are clustered either way.
  bool no_lines = false;
  /// Where the chain stops. With a triangle count or ratio, the chain ends at
  /// the first level with at most that many triangles (kTargetReached; the
  /// levels' counts are the octree's, so it may overshoot). With max_error,
  /// it ends at the last level whose `error` (below) is within the budget
  /// (kErrorBudgetReached). `{}`: the whole chain.
  SimplifyTarget target;
};

/// Clusters `mesh` into a chain of levels of detail; returns them coarser and
/// coarser, never empty:
/// * level 0 is the input with equal positions merged, vertices used by no
///   triangle or line left out, and the triangle rules above applied
///   (duplicate triangles dropped, degenerate ones turned into lines or
///   dropped); `error` = 0;
/// * every further level has at most (1 - min_diff) x the vertices of the one
///   before (vertices whose triangles all vanished are left out), down to an
///   octree of depth 1 (at most 8 vertices) or a level with nothing left.
/// Each level's mesh carries the attributes of the input: vertex normals,
/// texcoords and colours of the original vertex in `vertex_map` (the
/// representative's; for a quadric-placed vertex, the nearest vertex of its
/// cell), materials of the original triangle in `face_map`. Vertices are in
/// octree (Morton) order, triangles sorted by their smallest vertex index
/// (each keeps its corner order, so its orientation), so that neighbours in
/// memory are neighbours in space; `face_map` gives the input triangle.
///
/// `error` of a level, in model units: the largest distance from an original
/// vertex (one still represented in the level) to its representative's
/// position, i.e. the largest vertex displacement, measured exactly. It is at
/// most the diagonal of the level's octree cell (sqrt(3) x the bounding-cube
/// side / 2^depth; `stop_detail` names the depth and cell). It is NOT a bound
/// on the surface deviation (Hausdorff distance) between the level and the
/// input: a surface crossing a cell can move further than its vertices, and
/// collapsed parts vanish. Measure that with metrics/compare_meshes.
///
/// `stop_reason` of the last level says why the chain ended (kTargetReached,
/// kErrorBudgetReached, kCannotSimplify: depth 1 reached or no level removes
/// min_diff of the vertices; kNoReduction: the target asks for none). Earlier
/// levels carry kNoReduction (level 0) or kTargetReached, meaning that level's
/// own min_diff step was met; `stop_detail` gives the octree depth, cell
/// diagonal and vertex drop of every level.
///
/// Time O(V + F) for level 0 (radix-sorted Morton codes) plus O(V + F) per
/// further level (cells with more than 64 vertices score 64 of them), so
/// O(V + F) in practice as the levels shrink geometrically. In parallel
/// (TBB): the cells of a level in tasks of 128 cells, a level's faces
/// remapped beside the choice of its vertices, a finished level copied into
/// its result beside the next level's work, and level 0's passes over the
/// input (bounds, codes, sort, merge, the counting sort of the triangles)
/// and each level's passes over its vertices in tasks of 16 384 items; the
/// result does not depend on the thread count. The area and volume
/// heuristics are summed in single precision relative to the cell's mean,
/// four triangles at a time, and only in cells with more than one contender
/// (see above). Memory: a few arrays of O(V + F) reused over the levels, on
/// TBB's scalable allocator (which keeps them for the next call), plus the
/// results. Throws
/// DataError if an index is out of range, a used coordinate is not finite or
/// an attribute array has the wrong length.
std::vector<SimplifyResult> vertex_clustering(const TriangleMesh& mesh,
                                              const VertexClusteringOptions& options = {});

}  // namespace lodforge
