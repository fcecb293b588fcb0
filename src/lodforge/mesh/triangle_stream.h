#pragma once
/// The triangles of a mesh file, visited chunk by chunk without holding the
/// mesh: the reader of out-of-core algorithms (simplify/out_of_core_clustering.h).
///
/// Formats (told from the content, not the extension):
///
/// | file                  | triangles                                  | vertices |
/// |-----------------------|--------------------------------------------|---------------------------|
/// | binary PLY (either    | element 'face', list 'vertex_indices' (or  | element 'vertex': x, y, z
/// | | byte order)           | 'vertex_index') of any integer type;       | of any numeric type, |
/// |                       | polygons fan-triangulated (c0 ci ci+1),    | other properties skipped;
/// | |                       | faces of fewer than 3 corners skipped;     | no list properties | |
/// | other face properties and other elements   |                           | | | skipped | | |
/// binary STL            | the records in order                       | each triangle's own three |
///
/// Refused with a DataError that says so: ASCII PLY, ASCII STL, other
/// formats, gzip-compressed files, PLY 'tristrips', standard input.
///
/// Memory: the faces are read sequentially through a buffer of 1 MiB, and a
/// PLY file's vertex block, which faces index at random, is mapped
/// read-only (core/file_io.h MappedFileRegion): the operating system pages it,
/// it takes address space but no heap. A chunk of triangles is
/// `chunk_triangles` x 60 bytes. Nothing else grows with the file.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>

#include "lodforge/core/math.h"
#include "lodforge/mesh/mesh_io.h"

namespace lodforge {

/// One triangle of a stream: its corners' positions and the input vertices
/// they are (PLY: the vertex's index; STL: 3 x triangle + corner).
struct StreamedTriangle {
  std::array<Vec3, 3> corner;
  std::array<std::uint64_t, 3> vertex;
};

struct TriangleStreamOptions {
  std::size_t chunk_triangles = std::size_t{1} << 16;  ///< triangles per visit (0: 1)
};

class TriangleStream {
 public:
  /// A visit of `chunk`, whose first triangle is the stream's triangle
  /// number `first` (triangles are numbered in file order after fan
  /// triangulation).
  using TriangleVisitor =
      std::function<void(std::span<const StreamedTriangle> chunk, std::uint64_t first)>;
  /// A visit of the positions of vertices [first, first + size).
  using VertexVisitor = std::function<void(std::span<const Vec3> vertices, std::uint64_t first)>;

  /// Opens `path` and reads its header (the PLY header; the STL triangle
  /// count, checked against the file size). Throws DataError naming the
  /// file and what was expected when it is unreadable, of a refused kind
  /// (see the table), or too short for what its header declares; ParseError
  /// for a malformed PLY header.
  explicit TriangleStream(const std::string& path, const TriangleStreamOptions& options = {});
  ~TriangleStream();
  TriangleStream(const TriangleStream&) = delete;
  TriangleStream& operator=(const TriangleStream&) = delete;

  /// True if `path` is a file the stream accepts (by its first bytes and
  /// size; the rest is checked while reading). Never throws.
  static bool accepts(const std::string& path);

  MeshFormat format() const;        ///< kPly or kStl
  std::uint64_t file_size() const;  ///< bytes
  /// PLY: the vertex element's count; STL: 3 x the triangle count.
  std::uint64_t vertex_count() const;
  /// PLY: the faces declared (polygons, before triangulation); STL: the triangles.
  std::uint64_t face_count() const;

  /// Calls `visit` for the triangles in file order, chunk by chunk (each
  /// chunk `chunk_triangles` long but the last), on the calling thread; each
  /// call reads the file again from the start. Throws DataError ("file: byte
  /// N: ...") for a truncated file, a vertex index out of range, a negative
  /// list length or a non-finite corner coordinate; the chunks visited
  /// before the error have been visited. Returns the number of triangles.
  std::uint64_t for_each_triangle(const TriangleVisitor& visit) const;

  /// Calls `visit` for the vertices in index order, in chunks (PLY: every
  /// vertex of the element, used by a face or not; STL: the corners, vertex
  /// 3t + k being corner k of triangle t). Throws DataError for a
  /// non-finite coordinate or a truncated file.
  void for_each_vertex(const VertexVisitor& visit) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lodforge
