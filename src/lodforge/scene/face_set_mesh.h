#pragma once
/// The one path from an indexed face set to triangles, shared by every
/// reader of indexed faces (VRML 1.0 and Inventor shapes, their LOD reader,
/// the VRML97 / X3D LOD reader): the faces of a coordIndex, each index
/// checked against the coordinates, and the triangles of each face over the
/// caller's mesh vertices. Readers differ in what a mesh vertex is (one per
/// coordinate, or one per distinct tuple of attributes at a corner), so the
/// caller maps corners to vertices between the two steps.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/mesh/triangulate_polygon.h"
#include "lodforge/scene/attribute_binding.h"

namespace lodforge::scene {

/// What face_runs names in its error.
struct FaceSetSource {
  std::string_view where;        ///< the node, e.g. "line 4: IndexedFaceSet"
  std::string_view coordinates;  ///< the node holding the points, e.g. "Coordinate3"
};

/// A face (or an IndexedLineSet's polyline): [begin, end) positions in coordIndex.
using FaceRun = std::pair<std::size_t, std::size_t>;

/// Calls visit(begin, end) for each face of `index` in order: the non-empty
/// runs separated by -1 (any negative index); a missing final -1 is allowed.
/// No index is checked (face_runs checks them).
template <class Visit>
void for_each_index_run(std::span<const std::int32_t> index, Visit&& visit) {
  std::size_t begin = 0;
  for (std::size_t i = 0; i < index.size(); ++i)
    if (index[i] < 0) {
      if (i > begin) visit(begin, i);
      begin = i + 1;
    }
  if (index.size() > begin) visit(begin, index.size());
}

/// Throws DataError "<where> coordIndex[i] = v is out of range (the current
/// <coordinates> has n points)" naming the first index of `coord_index` out of
/// range of `point_count` (negative indices end faces). O(coord_index.size()).
void check_coord_index(std::span<const std::int32_t> coord_index, std::size_t point_count,
                       const FaceSetSource& source);

/// The faces of `coord_index` in order: the non-empty runs separated by -1
/// (any negative index); a missing final -1 is allowed. Every index is
/// checked first (check_coord_index). O(coord_index.size()).
std::vector<FaceRun> face_runs(std::span<const std::int32_t> coord_index, std::size_t point_count,
                               const FaceSetSource& source);

/// One attribute of an indexed face set bound to its corners: VRML 1.0's
/// materials, normals and texture coordinates under their binding
/// (attribute_binding.h), VRML97 / X3D's normals, colours and texture
/// coordinates (vrml97_binding).
struct FaceSetAttribute {
  AttributeIndexer indexer;      ///< binding, index field, coordIndex
  std::size_t count = 0;         ///< values in the attribute's list
  std::string_view index_field;  ///< named in errors, e.g. "materialIndex", "colorIndex"
};

/// The binding of a VRML97 / X3D attribute (colorPerVertex /
/// normalPerVertex, and whether its index field is given): per vertex by the
/// index field, or by coordIndex when it is empty; per face by the index
/// field, or face by face when it is empty. Texture coordinates are always
/// per vertex.
Binding vrml97_binding(bool per_vertex, bool has_index);

/// The value of `attribute` at corner `corner_seq` (counted over the whole
/// face set) of face `face`, at position `pos` of coordIndex: an index into
/// the attribute's list, or -1 under OVERALL. One rule for every reader: a
/// value index that is negative, past the list, or missing (index field too
/// short) is an error. Throws DataError "<where> <field>[k] = v is out of
/// range (n values)" or "<where> <field> has no entry k (n entries)", where
/// <field> is coordIndex when PER_VERTEX_INDEXED reads it; a binding without
/// an index field says "<where> PER_FACE binding: face k takes value v, out
/// of range (n values)" (PER_VERTEX: corner k). O(1).
std::int64_t corner_attribute(const FaceSetAttribute& attribute, std::size_t face,
                              std::size_t corner_seq, std::size_t pos, std::string_view where);

/// How face_triangles treats a face.
struct FaceTriangulation {
  TriangulateOptions triangulation;  ///< quad rule (keep_quads false: no quad is reported)
  /// Corners repeating the corner before them, and last corners repeating
  /// the first, are merged first: a face of three distinct vertices is then
  /// one triangle.
  bool merge_repeated_corners = false;
  /// Triangles that use one vertex twice are left out.
  bool drop_repeated_vertex_triangles = false;
  /// Fill FaceTriangles::degenerate for triangles too (a face of more
  /// corners always gets its flags).
  bool diagnose_triangles = true;
};

/// What face_triangles did with a face.
struct FaceTriangles {
  std::size_t corners = 0;    ///< after merging; fewer than 3: nothing was appended
  std::size_t triangles = 0;  ///< appended
  bool keep_as_quad = false;  ///< four corners, convex and flat enough to stay a quad
  bool degenerate = false;    ///< (almost) no area
  bool not_simple = false;    ///< self-intersecting: triangulated anyway
};

/// Appends the triangles of one face to `triangles`: `poly` holds its mesh
/// vertices, one per corner in order (merged in place when asked), indexing
/// `positions`. Concave and non-planar faces are triangulated by ear
/// clipping (triangulate_polygon); a triangle passes as it is; the output is
/// wound like the face. Never throws. O(n^2) in the corners at worst.
FaceTriangles face_triangles(std::span<const Vec3> positions, std::vector<std::uint32_t>& poly,
                             const FaceTriangulation& options, std::vector<Triangle>& triangles);

}  // namespace lodforge::scene
