#pragma once
/// Level 0 of vertex_clustering (see vertex_clustering.h for the contract):
/// the input checked, its used coordinates sorted into octree order with
/// equal ones merged, and its faces under the face rules. Internal to
/// simplify/.
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/simplify/detail/clustering_cut.h"
#include "lodforge/simplify/detail/clustering_faces.h"

namespace lodforge::detail::clustering {

/// Fills `cut` with level 0 of `mesh` and returns the octree over it:
/// * the vertices used by a triangle or line, one per distinct coordinate,
///   in octree order (sorted by Morton code, then position), each with its
///   code, weight 1 and the first input vertex (in octree order) at it;
///   those nothing uses any more (every triangle around them collapsed and
///   no line) left out;
/// * the triangles with three distinct vertices sorted by their smallest
///   vertex (stably: in input order within a vertex), doublets dropped (the
///   first stays), those that collapse to a line as lines unless `no_lines`,
///   and the lines under the rules of finish_faces.
/// Throws DataError if an index is out of range, a used coordinate is not
/// finite or an attribute array has the wrong length (naming the first
/// offender). `scratch` is the remap's, kept for the levels to come.
/// Parallel (TBB) in its passes over the input; the result does not depend
/// on the thread count.
Octree build_level0(const TriangleMesh& mesh, bool no_lines, Cut& cut, RemapScratch& scratch);

}  // namespace lodforge::detail::clustering
