#pragma once
/// The geometry of one shape met by the traversal, as a triangle mesh:
/// IndexedFaceSet faces triangulated (concave and non-planar faces too),
/// IndexedLineSet polylines as segments, PointSet points as vertices,
/// primitives tessellated (by the state's Complexity), Inventor's FaceSet,
/// TriangleStripSet, IndexedTriangleStripSet and QuadMesh as the faces of
/// their IndexedFaceSet equivalent, LineSet as segments (inventor_shapes.h).
/// AsciiText has no geometry here.
#include "lodforge/core/log.h"
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/mesh/triangulate_polygon.h"
#include "lodforge/scene/tessellate_primitive.h"
#include "lodforge/scene/traverse.h"

namespace lodforge::scene {

struct ShapeMeshOptions {
  bool world_space = true;  ///< apply the traversal's transform
  TessellateOptions tessellation;
  TriangulateOptions triangulation;
};

/// Positions and triangles (and segments) of the shape. Throws DataError
/// ("line N: ...") for an index out of range or non-finite coordinates.
/// Degenerate and non-simple faces are triangulated anyway and reported to
/// `log` (category triangulator) when given.
TriangleMesh shape_mesh(const ShapeVisit& visit, const ShapeMeshOptions& options = {},
                        Log* log = nullptr);

/// Faces of an IndexedFaceSet's coordIndex (or polylines of an
/// IndexedLineSet): runs separated by -1; a missing final -1 is allowed.
/// Returns [begin, end) ranges into `index`.
std::vector<std::pair<std::size_t, std::size_t>> split_index_runs(
    const std::vector<std::int32_t>& index);

}  // namespace lodforge::scene
