#pragma once
/// VRML97 (`#VRML V2.0 utf8`) and X3D classic encoding (`#X3D V3.x utf8`,
/// V4.x) reader, into the format-neutral scene graph (scene/node.h).
///
/// Grammar (ISO/IEC 14772-1 annex A; X3D adds header statements):
///   file      := header statement*
///   statement := node | PROTO | EXTERNPROTO | ROUTE
///                | PROFILE | COMPONENT | META | UNIT | IMPORT | EXPORT
///   node      := "DEF" NAME TYPE "{" body "}" | "USE" NAME | "NULL" | TYPE "{" body "}"
///   body      := (FIELD value | ROUTE | PROTO | EXTERNPROTO | declaration)*
///
/// Grouping is a field: a node's children are the nodes of its MFNode field
/// `children` (`level` of a VRML97 LOD, `choice` of a Switch), held as
/// FieldKind::kNode values; Node::children stays empty.
///
/// Fields of the nodes the LOD pipeline interprets (Transform, Shape,
/// IndexedFaceSet, Coordinate, LOD, Viewpoint, ...) are typed. Any other
/// field is typed by its lexical form: a node, DEF, USE or NULL (or a list of
/// them) is an SFNode (MFNode) value whose DEFs are bound; anything else is
/// kept as raw text. Statements (PROTO, EXTERNPROTO, ROUTE, PROFILE,
/// COMPONENT, META, UNIT, IMPORT, EXPORT) are kept verbatim: at top level as
/// nodes with `statement` set (type = keyword, raw_body = the rest), in a
/// node body as raw fields named by the keyword. Interface declarations of
/// Script and shader nodes (`field SFFloat x 1`, `inputOnly SFTime t`) are
/// fields whose name holds the access, type and name; their SFNode / MFNode
/// values are parsed as nodes, other values kept raw.
#include <string>
#include <string_view>

#include "lodforge/core/log.h"
#include "lodforge/scene/node.h"

namespace lodforge::vrml97 {

struct ReadOptions {
  std::string source_name = "<input>";  ///< used in messages ("file:line:col: ...")
  /// Deeper nesting than this is an error: the parser, the writer and the
  /// traversals recurse once per level.
  int max_depth = 256;
  /// The text is a PROTO's body: a field may be `NAME IS INTERFACE_FIELD`
  /// (kept as a raw field whose raw text is "IS INTERFACE_FIELD"), which is
  /// an error elsewhere.
  bool proto_body = false;
};

struct ReadResult {
  scene::Scene scene;  ///< header: the file's first line ("#VRML V2.0 utf8", "#X3D V3.2 utf8")
  Log log;
};

/// True if `header` is a VRML97 or X3D classic header.
bool is_vrml97_header(std::string_view header);
/// True if `header` is an X3D classic header ("#X3D V...").
bool is_x3d_header(std::string_view header);

/// The type of field `field` of node type `node_type` if the reader types it
/// (the fields of the nodes the LOD pipeline interprets); false for any other.
bool typed_field(std::string_view node_type, std::string_view field, scene::FieldType& out);

/// Parses VRML97 / X3D classic text. Throws ParseError ("file:line:col:
/// expected X, got Y") on a syntax error, a wrong header, a USE of an
/// undefined name, a wrong value of a typed field or nesting deeper than
/// max_depth.
ReadResult read_vrml97(std::string_view text, const ReadOptions& options = {});

/// Reads a file ("-" = standard input; gzip-compressed data is decompressed).
/// Throws DataError / ParseError.
ReadResult read_vrml97_file(const std::string& path, ReadOptions options = {});

}  // namespace lodforge::vrml97
