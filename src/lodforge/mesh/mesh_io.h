#pragma once
/// Reading and writing mesh files: PLY (ASCII and binary), OBJ, OFF, STL.
/// The format is chosen by the file's extension (and, when reading, checked
/// against its content). Polygons are triangulated on reading.
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

/// Reads a mesh file ("-" = standard input, format then required). Throws
/// ParseError (file:line:col for text formats) or DataError on bad input.
TriangleMesh read_mesh(const std::string& path, const MeshReadOptions& options = {});

/// Parses mesh data held in memory; `source_name` is used in messages.
TriangleMesh read_mesh_data(std::string_view data, MeshFormat format,
                            const std::string& source_name, const MeshReadOptions& options = {});

/// Writes a mesh atomically (temporary file, then rename). Throws DataError.
void write_mesh(const TriangleMesh& mesh, const std::string& path,
                const MeshWriteOptions& options = {});

/// The format a path's extension names (kAuto if none matches).
MeshFormat format_from_path(std::string_view path);

}  // namespace lodforge
