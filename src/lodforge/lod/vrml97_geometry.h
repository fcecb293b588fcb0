#pragma once
/// The polygons of a VRML97 / X3D geometry node (IndexedFaceSet,
/// IndexedTriangleSet, TriangleSet, IndexedQuadSet, ElevationGrid) as corner
/// tuples of (coordinate, normal, texture coordinate, colour) indices, and the
/// mesh they make: one vertex per distinct tuple, so every attribute can
/// follow a vertex back into the node it came from. Shared by the VRML97 LOD
/// pipeline and the flattening of a VRML97 scene into one mesh.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "lodforge/core/log.h"
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/mesh/triangulate_polygon.h"
#include "lodforge/scene/node.h"

namespace lodforge::vrml97_geometry {

using scene::Node;
using scene::NodePtr;

bool is_supported_geometry(const std::string& type);
// The fields whose nodes are children, where a LOD can stand for a Shape.
bool is_child_list(std::string_view field);
NodePtr node_of(const Node& n, std::string_view field);
bool bool_of(const Node& n, std::string_view field, bool fallback);
const std::vector<std::int32_t>* ints_of(const Node& n, std::string_view field);
// The values of an attribute node's array field, and how many there are.
std::size_t attribute_count(const NodePtr& n, std::string_view field);

/// The coordinate lists of a texCoord node: the node itself when it is a
/// TextureCoordinate, TextureCoordinate3D or TextureCoordinate4D; a
/// MultiTextureCoordinate's such children (one texCoordIndex indexes them
/// all); none for a node that computes its coordinates
/// (TextureCoordinateGenerator, Castle's ProjectedTextureCoordinate, ...).
std::vector<NodePtr> texture_coordinate_lists(const NodePtr& tex);

/// The first 2D coordinate list of `tex` (a TextureCoordinate; of a
/// MultiTextureCoordinate, its first texture's), or null.
NodePtr first_texture_coordinates(const NodePtr& tex);

// One corner's indices into the coordinate, normal, texture coordinate and
// colour nodes (kNone: the attribute is absent or bound per face).
using Corner = std::array<std::uint32_t, 4>;

struct CornerHash {
  std::size_t operator()(const Corner& c) const {
    std::size_t h = 1469598103934665603ull;
    for (std::uint32_t v : c) h = (h ^ v) * 1099511628211ull;
    return h;
  }
};

// The polygons of a geometry node as corner tuples, with per-face attributes.
struct Polygons {
  std::vector<std::uint32_t> start{0};  ///< polygon p: corners [start[p], start[p+1])
  std::vector<Corner> corners;
  std::vector<std::uint32_t> face_normal, face_color;  ///< per polygon, when bound per face
};

// One attribute of a geometry node: its node, per vertex or per face, and
// the index field that indexes it (IndexedFaceSet only).
struct Attribute {
  NodePtr node;
  std::size_t count = 0;
  bool per_vertex = true;
  const std::vector<std::int32_t>* index = nullptr;
  std::string_view index_field;
  std::string error;  ///< the first bad index found (the attribute is dropped)
  /// Texture coordinates the node computes for whatever geometry uses it
  /// (TextureCoordinateGenerator; Castle's ProjectedTextureCoordinate and
  /// MultiGeneratedTextureCoordinate; a MultiTextureCoordinate of those):
  /// nothing to index, every level uses the node as it is.
  bool generated = false;
};

/// Corners a face of an IndexedTriangleSet / TriangleSet (3) or an
/// IndexedQuadSet (4).
std::size_t corners_per_face(const Node& set);

/// The coordinate indices of such a set's corners, face after face: its
/// `index`, or for a TriangleSet without one its coordinates in order.
std::vector<std::int32_t> set_corner_order(const Node& set);

class GeometryReader {
 public:
  GeometryReader(const Node& g, Log& log, const std::string& where);

  /// False (with a warning) if the shape cannot be read as it is.
  bool read(Polygons& out);

  const NodePtr& coord() const { return coord_; }
  const Attribute& normal() const { return normal_; }
  const Attribute& tex() const { return tex_; }
  const Attribute& color() const { return color_; }

 private:
  void read_indexed_face_set(Polygons& out);

  // IndexedTriangleSet / IndexedQuadSet (`index`) and TriangleSet (the
  // coordinates in order): attributes are indexed like the coordinates.
  void read_triangle_sets(Polygons& out);

  int int_of(std::string_view field) const;
  float float_of(std::string_view field) const;

  // An ElevationGrid's points and its default texture coordinates (s along
  // x, t along z: X3D 13.3.4) as nodes, so its levels are IndexedFaceSets.
  void elevation_grid_nodes();

  // Quads (x, z), (x, z+1), (x+1, z+1), (x+1, z): counter-clockwise seen
  // from +y; attributes per vertex by the vertex number, per face by the quad's.
  void read_elevation_grid(Polygons& out);

  // Face `face`: the corners at [b, e) of the coordinate index `ci`, each
  // with its per-vertex attribute values, and the face's per-face values.
  void add_face(Polygons& out, const std::vector<std::int32_t>& ci, std::size_t face, std::size_t b,
                std::size_t e);

  // The value of attribute `a` at a corner (per_vertex) or a face, by the
  // one face-set rule (scene::corner_attribute); kNone when it is not bound
  // that way or the index is bad (the first bad index is kept in a.error).
  std::uint32_t value(Attribute& a, bool per_vertex, const std::vector<std::int32_t>& ci,
                      std::size_t face, std::size_t pos);

  // An attribute with a bad index is dropped (browsers generate normals, or
  // draw without texture coordinates or colours).
  void drop_bad(Polygons& out, Attribute& a, std::size_t slot, std::vector<std::uint32_t>* per_face,
                std::string_view what);

  const Node& g_;
  Log& log_;
  std::string where_, node_where_;
  NodePtr coord_;
  std::size_t coords_ = 0;
  Attribute normal_, tex_, color_;
};

/// A shape's mesh: a vertex per distinct corner tuple.
struct ShapeMesh {
  TriangleMesh mesh;
  std::vector<Corner> vertex_corner;            ///< #V of mesh
  std::vector<std::uint32_t> triangle_polygon;  ///< #F of mesh: its polygon
};

/// The mesh of the polygons `reader` read (triangulated by `triangulation`,
/// quads split, triangles with a repeated vertex dropped).
void build_mesh(const Polygons& p, const GeometryReader& reader,
                const TriangulateOptions& triangulation, ShapeMesh& out);

}  // namespace lodforge::vrml97_geometry
