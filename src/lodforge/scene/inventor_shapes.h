#pragma once
/// Open Inventor's vertex shapes without a VRML 1.0 counterpart (FaceSet,
/// TriangleStripSet, IndexedTriangleStripSet, QuadMesh, LineSet) as the
/// IndexedFaceSet or IndexedLineSet that draws the same faces or polylines
/// with the same attributes, so metrics, rendering and the LOD pipeline treat
/// them as they treat VRML 1.0's indexed sets.
///
/// Geometry, as Inventor draws it (Coin 4.0):
///  - FaceSet: face f takes numVertices[f] consecutive coordinates from
///    startIndex on (-1: all that are left);
///  - TriangleStripSet: strip s takes numVertices[s] consecutive coordinates;
///    its triangle i is (v_i, v_i+1, v_i+2) for even i, (v_i+1, v_i, v_i+2) for
///    odd i, so all face the same way;
///  - IndexedTriangleStripSet: strips are runs of coordIndex separated by -1;
///  - QuadMesh: verticesPerColumn rows of verticesPerRow coordinates; quad
///    (r, c) is (r,c) (r,c+1) (r+1,c+1) (r+1,c);
///  - LineSet: polyline p takes numVertices[p] consecutive coordinates.
///
/// Attributes: the state's bindings are rewritten as PER_FACE_INDEXED or
/// PER_VERTEX_INDEXED with the index lists Inventor's rules give: PER_PART is
/// per face (FaceSet), per strip, per row of quads (QuadMesh), per polyline;
/// PER_FACE per face, triangle or quad; PER_VERTEX counts the vertices the
/// shape uses from 0 (startIndex not included: Inventor binds attributes to
/// the shape's vertices, not to the coordinates). The non-indexed shapes
/// treat the *_INDEXED bindings as the plain ones; the indexed strip set
/// reads materialIndex / normalIndex / textureCoordIndex (or coordIndex where
/// those are left at their default). Normals bind PER_VERTEX by default,
/// materials OVERALL.
#include <string_view>
#include <vector>

#include "lodforge/scene/node.h"
#include "lodforge/scene/traverse.h"

namespace lodforge::scene {

/// True for the types to_indexed_shape converts.
bool has_indexed_equivalent(std::string_view type);

struct IndexedEquivalent {
  NodePtr shape;               ///< an IndexedFaceSet or IndexedLineSet (first_line of the input)
  TraversalState state;        ///< the visit's state, bindings rewritten for `shape`
  std::vector<NodePtr> owned;  ///< the binding nodes `state` points to
};

/// The indexed equivalent of `visit.shape` under `visit.state` (types of
/// has_indexed_equivalent). Throws DataError ("line N: ...") when the shape
/// uses more coordinates than the state holds, or a coordIndex out of range.
IndexedEquivalent to_indexed_shape(const ShapeVisit& visit);

}  // namespace lodforge::scene
