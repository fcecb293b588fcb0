#pragma once
/// The geometry of one shape met by the traversal, as a triangle mesh:
/// IndexedFaceSet faces triangulated (concave and non-planar faces too),
/// IndexedLineSet polylines as segments, PointSet points as vertices,
/// primitives tessellated (by the state's Complexity), Inventor's FaceSet,
/// TriangleStripSet, IndexedTriangleStripSet and QuadMesh as the faces of
/// their IndexedFaceSet equivalent, LineSet as segments (inventor_shapes.h).
/// AsciiText has no geometry here.
#include <vector>

#include "lodforge/core/log.h"
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/mesh/triangulate_polygon.h"
#include "lodforge/scene/face_set_mesh.h"
#include "lodforge/scene/tessellate_primitive.h"
#include "lodforge/scene/traverse.h"

namespace lodforge::scene {

struct ShapeMeshOptions {
  bool world_space = true;  ///< apply the traversal's transform
  /// Also what the shape looks like (shape_surface): per-vertex colours from
  /// the current Material and MaterialBinding, opacity, and texture
  /// coordinates under a Texture2. Vertices are then split where corners at
  /// one coordinate differ in colour or texture coordinate.
  bool appearance = false;
  TessellateOptions tessellation;
  TriangulateOptions triangulation;
};

/// Positions and triangles (and segments) of the shape. Throws DataError
/// ("line N: ...") for an index out of range or non-finite coordinates.
/// Degenerate and non-simple faces are triangulated anyway and reported to
/// `log` (category triangulator) when given.
TriangleMesh shape_mesh(const ShapeVisit& visit, const ShapeMeshOptions& options = {},
                        Log* log = nullptr);

/// What shape_mesh(visit, options) holds, counted: an IndexedFaceSet's or
/// IndexedLineSet's faces are counted from coordIndex without being
/// triangulated (a face of n >= 3 corners is n - 2 triangles), other shapes
/// are built. Throws the DataErrors of shape_mesh.
struct ShapeCounts {
  std::size_t triangles = 0;
  std::size_t vertices = 0;
  std::size_t segments = 0;
  Box3 bounds;  ///< of the positions, in world space with options.world_space
};
ShapeCounts shape_counts(const ShapeVisit& visit, const ShapeMeshOptions& options = {});

/// A shape's mesh with its appearance (ShapeMeshOptions::appearance).
///
/// Colours follow the VRML 1.0 lighting of a Material row as closely as one
/// RGB per vertex can: diffuseColor + emissiveColor, clamped to [0,1]
/// (ambient and specular are the renderer's). A Material field with fewer
/// values than the row asked for repeats its last value. Bindings as
/// attribute_binding.h reads them on IndexedFaceSet and IndexedLineSet (and
/// Inventor's strips, face sets and quad meshes through their indexed
/// equivalent); primitives and PointSet take the first row. An index out of
/// range takes row 0, with a warning in `log` (category material).
///
/// Texture coordinates, when the state's Texture2 has a filename or an
/// image: an indexed set reads TextureCoordinate2 through textureCoordIndex
/// (its default: coordIndex); without a TextureCoordinate2 node (or with an
/// index out of range) it gets the VRML 1.0 default mapping: s along the
/// longest side of the shape's bounding box from 0 to 1, t along the second
/// longest from 0 to its length over the longest. Primitives use the
/// mapping the specification gives them (tessellate_primitive.h).
struct ShapeSurface {
  TriangleMesh mesh;              ///< as shape_mesh, plus colors (#V) and texcoords (#V or empty)
  std::vector<float> opacity;     ///< #V, 1 - transparency
  const Node* texture = nullptr;  ///< the Texture2 drawn on the triangles, or nullptr
};

/// As shape_mesh, with appearance (options.appearance is taken as true).
ShapeSurface shape_surface(const ShapeVisit& visit, const ShapeMeshOptions& options = {},
                           Log* log = nullptr);

}  // namespace lodforge::scene
