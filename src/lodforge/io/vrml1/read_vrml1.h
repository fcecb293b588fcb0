#pragma once
/// VRML 1.0 reader: a hand-written lexer and recursive-descent parser for the
/// whole VRML 1.0 specification (and the Open Inventor 2.x ASCII files that
/// share its grammar).
///
/// Grammar (after Coin's SoBase/SoFieldData, without their registries):
///   file    := header node*
///   node    := "DEF" NAME node-body | "USE" NAME | node-body
///   body    := TYPE "{" ["fields" "[" decl ("," decl)* "]"] ["isA" "[" STRING* "]"]
///              (FIELD value | node)* "}"
///
/// Unknown node types are kept: with a `fields [...]` declaration they are
/// parsed like any node; without one, their body is kept verbatim. Unknown
/// fields of known nodes are kept verbatim too. Both produce a warning naming
/// the node and its line range.
///
/// Open Inventor 2.x ASCII (a `#Inventor V2.1 ascii` header, or V2.0, V1.0):
/// the Inventor node types and fields of the schema (scene/schema.h) are known
/// as well, SFNode fields (a shape's `vertexProperty VertexProperty { ... }`)
/// hold nodes, and a value may carry the ignore flag `~` or a connection
/// `= Engine { ... } . output` (both kept, and written back). Other Inventor
/// nodes (DrawStyle, Text2, engines, ...) are unknown nodes, kept verbatim.
#include <cstdint>
#include <string>
#include <string_view>

#include "lodforge/core/log.h"
#include "lodforge/scene/node.h"

namespace lodforge::vrml1 {

struct ReadOptions {
  /// Name used in messages ("file:line:col: ...").
  std::string source_name = "<input>";
  /// Read the local files of WWWInline nodes (relative to `base_dir`) and put
  /// their scenes under the WWWInline as children. Never reads over a network;
  /// refuses paths that leave `base_dir`.
  bool read_inlines = false;
  std::string base_dir = ".";
  /// Deeper nesting than this is an error: the parser, the writer and the
  /// traversals recurse once per level, and this bound keeps them within the
  /// stack even in sanitizer builds (real files nest a few dozen levels).
  /// The nodes of an inlined file count from the depth of their WWWInline, so
  /// the bound holds for the whole scene, inlines included.
  int max_depth = 256;
  /// The scene may expand to at most this many node instances: a node counts
  /// once for each path from a root to it, so DEF/USE sharing and inlines
  /// multiply (a scene that doubles its instances at each of 40 levels is
  /// refused while it is read, before any traversal does the work). 0: no
  /// limit.
  std::uint64_t max_instances = 10'000'000;
  /// The shapes of the expanded scene may draw at most this many triangles
  /// (estimated as nodes are read: an IndexedFaceSet its faces' triangles,
  /// an IndexedLineSet its segments, a PointSet its points, a primitive its
  /// default tessellation). 0: no limit.
  std::uint64_t max_triangles = 10'000'000;
  /// At most this many WWWInline files are read in all (each inlined file
  /// counts each time it is inlined). 0: no limit.
  std::uint64_t max_inline_files = 10'000;
};

struct ReadResult {
  scene::Scene scene;
  Log log;  ///< warnings: unknown nodes and fields, inlines, suspicious values
};

/// Parses VRML 1.0 text. Throws ParseError ("file:line:col: expected X, got Y")
/// on any syntax error, an unknown USE name, a wrong value for a field,
/// nesting deeper than max_depth, more than max_instances instances or max_triangles triangles.
/// With read_inlines, throws DataError naming the file and line of the WWWInline for an inline that
/// leaves base_dir, is not a regular file (a FIFO, a device), cannot be resolved (a symbolic link
/// loop), or goes past max_inline_files.
ReadResult read_vrml1(std::string_view text, const ReadOptions& options = {});

/// Reads a file ("-" = standard input; gzip-compressed data is decompressed),
/// setting source_name and base_dir from the path. Throws DataError/ParseError.
ReadResult read_vrml1_file(const std::string& path, ReadOptions options = {});

}  // namespace lodforge::vrml1
