#pragma once
/// X3D XML encoding (`.x3d`, ISO/IEC 19776-1) reader, into the scene model the
/// X3D classic reader (io/vrml97/read_vrml97.h) produces, so that `lod` and the
/// classic writer work on it unchanged.
///
/// The document is parsed with pugixml and restated in the classic encoding,
/// which read_vrml97 then parses: one element per line, so a classic parse
/// error maps back to the element's line and column in the XML file.
///   <X3D version profile>           -> header "#X3D V<version> utf8", PROFILE
///   <head> component / unit / meta  -> COMPONENT / UNIT / META statements
///   <Type DEF USE containerField>   -> node; its attributes are fields, its
///                                      child elements the nodes of the field
///                                      named by containerField (or the
///                                      child type's default field)
///   ROUTE, IMPORT, EXPORT           -> statements
///   ProtoDeclare, ExternProtoDeclare -> PROTO / EXTERNPROTO (IS / connect as
///                                      `field IS protoField`)
///   ProtoInstance + fieldValue      -> a node of the prototype's type
///   <field> of Script and shaders   -> interface declarations
///   CDATA of Script / ShaderPart    -> one more `url` string
/// Attribute values are typed as X3D types them: a list of several numbers
/// is an MF value unless the field is a known single vector (translation,
/// diffuseColor, ...), a word that is not a number is a string.
#include <string>
#include <string_view>

#include "lodforge/io/vrml97/read_vrml97.h"

namespace lodforge::x3dxml {

/// True if `head` (the first bytes of a file) starts an XML document.
bool is_xml_start(std::string_view head);

/// Parses X3D XML text. Throws ParseError ("file:line:col: ...") on malformed
/// XML, a document that is not X3D, a USE of an undefined name or a value a
/// typed field cannot take.
vrml97::ReadResult read_x3d_xml(std::string_view text, const vrml97::ReadOptions& options = {});

/// Reads a file ("-" = standard input; gzip-compressed data is decompressed).
/// Throws DataError / ParseError.
vrml97::ReadResult read_x3d_xml_file(const std::string& path, vrml97::ReadOptions options = {});

/// The classic-encoding text read_x3d_xml parses (for tests and messages).
std::string x3d_xml_to_classic(std::string_view text, const std::string& source_name);

}  // namespace lodforge::x3dxml
