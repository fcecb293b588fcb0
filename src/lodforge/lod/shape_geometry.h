#pragma once
/// An IndexedFaceSet or IndexedLineSet (or an Inventor FaceSet, strip set,
/// QuadMesh or LineSet, read as its indexed equivalent: inventor_shapes.h)
/// with its traversal state, turned into a mesh the simplifiers work on, and
/// back into VRML nodes.
///
/// Vertices of the mesh are the distinct (coordinate, normal, texture
/// coordinate, per-vertex material) tuples of the shape's corners: a vertex is
/// split where its corners differ in an attribute (a seam), so every attribute
/// can follow a simplified vertex through the simplifier's vertex map.
/// Per-face attributes (PER_FACE / PER_PART materials or normals) follow the
/// face map. Bindings that are 1:1 with faces or vertices (PER_FACE, PER_PART,
/// PER_VERTEX) are converted to their *_INDEXED forms (original §4 intro).
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "lodforge/core/log.h"
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/mesh/triangulate_polygon.h"
#include "lodforge/scene/node.h"
#include "lodforge/scene/traverse.h"

namespace lodforge {

/// How an attribute is bound after conversion.
enum class AttributeBinding { kNone, kPerFace, kPerVertex };

struct ShapeGeometry {
  /// Local coordinates. mesh.materials holds the material of each triangle when
  /// materials are per face. mesh.lines holds the segments of a line set.
  TriangleMesh mesh;
  /// #F: the polygon of the input each triangle comes from.
  std::vector<std::uint32_t> triangle_polygon;
  /// Polygons that stay quads when both their triangles survive unchanged.
  std::vector<bool> polygon_is_quad;

  AttributeBinding material_binding = AttributeBinding::kNone;
  AttributeBinding normal_binding = AttributeBinding::kNone;
  bool has_texcoords = false;

  /// Distinct attribute values, and the index of each mesh vertex's value
  /// (#V; per-vertex bindings) or each triangle's (#F; per-face bindings).
  std::vector<Vec3> normal_values;
  std::vector<Vec2> texcoord_values;
  std::vector<std::uint32_t> vertex_normal, vertex_texcoord, vertex_material;
  std::vector<std::uint32_t> face_normal;       ///< #F, for per-face normals
  std::vector<std::uint32_t> segment_material;  ///< #L, line sets with materials
  /// #V: the material of a face using the vertex (per-face materials), for
  /// the lines that faces collapse into.
  std::vector<std::uint32_t> vertex_face_material;

  /// Distinct materials (rows of the Material node's parallel fields), in
  /// first-use order; empty when the material binding is kNone.
  scene::NodePtr material;
  /// The faceType of the input was not CONVEX (so an extra ShapeHints with
  /// faceType CONVEX is written: the output is triangles and convex quads).
  bool needs_convex_hint = false;
  /// The state holds attribute nodes this geometry does not use (no binding,
  /// or dropped for bad indices). Levels must then override them, or a
  /// reader would index the inherited values with coordIndex (out of range:
  /// Coin crashes): levels get an empty Normal / TextureCoordinate2 (the
  /// browser generates them) and the subtree a MaterialBinding OVERALL.
  bool override_normals = false;
  bool override_texcoords = false;
  bool override_material_binding = false;
  /// An index field of the input holds an index out of range (an attribute
  /// was dropped for it, or the field indexes nothing the state holds): the
  /// input node cannot be drawn as it is (Coin may crash on it).
  bool repaired = false;
  std::size_t input_faces = 0;    ///< polygons (or polylines) read
  std::size_t dropped_faces = 0;  ///< polygons with < 3 distinct corners
};

struct ShapeGeometryOptions {
  TriangulateOptions triangulation;  ///< quad split angle, --no-quads
};

/// Reads an IndexedFaceSet or IndexedLineSet under its state. Coordinates,
/// normals, texture coordinates and materials are de-duplicated. Throws
/// DataError ("line N: ...") for a coordIndex out of range or a non-finite
/// coordinate; an attribute index out of range drops that attribute with a
/// warning in `log`.
ShapeGeometry read_shape_geometry(const scene::ShapeVisit& visit,
                                  const ShapeGeometryOptions& options, Log& log);

/// Sets the override_* flags of `g` from the state it will be drawn under.
void mark_inherited_attributes(ShapeGeometry& g, const scene::TraversalState& state);

/// The levels of one shape as VRML, sharing one set of vertex data: one
/// Coordinate3 (and Normal / TextureCoordinate2 where the geometry has them)
/// holds every value the levels use, each once, in first-use order: a
/// position a simplifier left in place is reused by every level, a moved one
/// is appended. Each level is
///
///     Separator { [Material MaterialBinding] [NormalBinding] [ShapeHints]
///                 Coordinate3 [Normal] [TextureCoordinate2]
///                 IndexedFaceSet [IndexedLineSet] }
///
/// whose property nodes are the same nodes in every level (a writer DEFs
/// them in the first level and USEs them in the others), so the levels
/// carry nothing of the state they are drawn under. Faces that collapsed to
/// lines become the extra IndexedLineSet unless `no_lines`.
class LevelWriter {
 public:
  /// `geometry` must outlive the writer; `state` is the one the shape was
  /// read under (its ShapeHints is copied as CONVEX where needed).
  LevelWriter(const ShapeGeometry& geometry, const scene::TraversalState& state, bool no_lines);
  ~LevelWriter();
  LevelWriter(const LevelWriter&) = delete;
  LevelWriter& operator=(const LevelWriter&) = delete;

  /// One level: `mesh` is geometry.mesh itself (empty maps) or a simplified
  /// version of it with `vertex_map` (new -> geometry.mesh vertex) and
  /// `face_map` (new -> geometry.mesh triangle). The shared nodes are up to
  /// date after each call.
  scene::NodePtr level(const TriangleMesh& mesh, const std::vector<std::uint32_t>& vertex_map,
                       const std::vector<std::uint32_t>& face_map);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lodforge
