#pragma once
/// X3D XML encoding writer for the scene model of read_vrml97 / read_x3d_xml:
/// an `<X3D>` document with the header's version (3.0 for a VRML97 scene,
/// whose LOD `level` becomes `children`), the PROFILE, COMPONENT, UNIT and
/// META statements in `<head>`, nodes as elements (a field other than the
/// child type's default named by containerField; a shared node DEFined once,
/// then USEd; shared nodes without a name get one), typed values in X3D's
/// attribute syntax, values kept verbatim restated in it, interface
/// declarations as `<field>`, and ROUTE / IMPORT / EXPORT at the end of the
/// Scene. Text is escaped for XML (&, <, quotes, line breaks).
#include <string>

#include "lodforge/scene/node.h"

namespace lodforge::x3dxml {

/// The scene as X3D XML. Throws DataError if scene.header is not a VRML97 or
/// X3D header, or the scene holds a PROTO or EXTERNPROTO (their bodies are
/// kept as classic text, which this writer does not restate).
std::string write_x3d_xml(const scene::Scene& scene);

/// Writes the scene to `path` ("-" = standard output) through a temporary
/// file renamed into place (".gz": gzip-compressed). Throws DataError.
void write_x3d_xml_file(const scene::Scene& scene, const std::string& path);

}  // namespace lodforge::x3dxml
