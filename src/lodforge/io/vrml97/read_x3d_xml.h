#pragma once
/// X3D XML encoding reader (`.x3d`, ISO/IEC 19776-1), through Debian's
/// pugixml, into the scene graph read_vrml97 gives for the classic encoding
/// of the same scene (scene/node.h): the document is rewritten in the classic
/// encoding by the mapping between the two (19776-1 / 19776-2: elements are
/// nodes, attributes fields, child elements fill their containerField,
/// `field`, `fieldValue`, `IS`/`connect`, `ProtoDeclare`, `ExternProtoDeclare`,
/// `ProtoInstance`, `ROUTE`, `IMPORT`, `EXPORT` and the `head` statements
/// their classic forms, a Script's or shader's text its url), and that text
/// is read by read_vrml97. Every error names the XML file's line and column:
/// pugixml's for malformed XML, the element's or attribute's for a bad value.
#include <string>
#include <string_view>

#include "lodforge/io/vrml97/read_vrml97.h"

namespace lodforge::vrml97 {

/// True if `path` names an X3D XML file: it ends in .x3d, .x3d.gz or .x3dz.
bool is_x3d_xml_path(std::string_view path);

/// The classic encoding of an X3D XML document (what read_x3d_xml parses).
/// Throws ParseError naming the XML's line and column.
std::string x3d_xml_to_classic(std::string_view xml, const ReadOptions& options = {});

/// Parses an X3D XML document. The scene's header is the classic one of the
/// document's version ("#X3D V3.2 utf8"). Throws ParseError
/// ("file:line:col: ...") for malformed XML, a root other than <X3D>, a bad
/// value, a USE of an undefined name or nesting deeper than max_depth.
ReadResult read_x3d_xml(std::string_view xml, const ReadOptions& options = {});

/// Reads a file ("-" = standard input; gzip-compressed data is decompressed).
/// Throws DataError / ParseError.
ReadResult read_x3d_xml_file(const std::string& path, ReadOptions options = {});

}  // namespace lodforge::vrml97
