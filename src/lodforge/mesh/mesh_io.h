#pragma once
/// Reading and writing mesh files: PLY (ASCII and binary), OBJ, OFF, STL.
/// The format is chosen by the file's extension (and, when reading, checked
/// against its content); a trailing ".gz" is not part of it: "x.ply.gz" is a
/// PLY file, gzip-compressed. Polygons are triangulated on reading.
#include <string>
#include <string_view>

#include "lodforge/core/log.h"
#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

enum class MeshFormat { kAuto, kPly, kObj, kOff, kStl };

struct MeshReadOptions {
  MeshFormat format = MeshFormat::kAuto;  ///< kAuto: from extension, then content
  Log* log = nullptr;                     ///< warnings (skipped elements, ...)
};

struct MeshWriteOptions {
  MeshFormat format = MeshFormat::kAuto;  ///< kAuto: from the path's extension
  bool binary = true;                     ///< PLY and STL: binary (default) or ASCII
};

/// Reads a mesh file ("-" = standard input; without an extension the format
/// is told from the content). Gzip-compressed files are read transparently.
/// Polygons are triangulated (triangulate_polygon), normals made unit length.
/// Throws ParseError ("file:line:col: expected X, got Y") for text formats,
/// DataError ("file: byte N: ...") for binary ones, and DataError for an
/// unreadable file. Out-of-range indices and non-finite numbers are errors.
TriangleMesh read_mesh(const std::string& path, const MeshReadOptions& options = {});

/// Parses mesh data held in memory; `source_name` is used in messages.
TriangleMesh read_mesh_data(std::string_view data, MeshFormat format,
                            const std::string& source_name, const MeshReadOptions& options = {});

/// Writes a mesh atomically (temporary file, then rename); a path ending in
/// ".gz" is written gzip-compressed (write_file_atomic). Throws DataError.
void write_mesh(const TriangleMesh& mesh, const std::string& path,
                const MeshWriteOptions& options = {});

/// Serialises a mesh to the bytes of a file; `options.format` must not be
/// kAuto (DataError). What each format keeps:
///   PLY: positions, normals, colours (as uchar), texcoords (s t), materials
///        (face property material_index), lines (element edge)
///   OBJ: positions, colours (v x y z r g b), texcoords, normals, materials
///        (usemtl material_<i>), lines (l)
///   OFF: positions, normals, colours, texcoords ([ST][C][N]OFF), lines (2-gons)
///   STL: positions only (each triangle with its own corners)
/// Throws DataError if an attribute array does not match the vertex count or
/// an index is out of range.
std::string write_mesh_data(const TriangleMesh& mesh, const MeshWriteOptions& options);

/// The format a path's extension names, after dropping a ".gz" (kAuto if none matches).
MeshFormat format_from_path(std::string_view path);

}  // namespace lodforge
