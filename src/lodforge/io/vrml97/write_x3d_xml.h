#pragma once
/// X3D XML encoding writer (ISO/IEC 19776-1), through Debian's pugixml: the
/// scene graph of an X3D scene (header "#X3D V..."; a VRML97 scene is made
/// X3D first) as the XML document a reader of `.x3d` files takes. Nodes are
/// elements whose fields are attributes (`true`/`false`, SFString unquoted,
/// lists unbracketed) and whose node fields are child elements, named by
/// containerField where it is not the type's default; DEF/USE as attributes
/// (a shared node without a name gets one); PROFILE / COMPONENT / META /
/// UNIT in <head>; ROUTE, IMPORT and EXPORT as their elements; a PROTO as
/// <ProtoDeclare> (its interface as <field>s, its body, read anew from the
/// text the classic reader kept, as <ProtoBody> with <IS>/<connect>), an
/// EXTERNPROTO as <ExternProtoDeclare>, an instance of either as
/// <ProtoInstance> with <fieldValue>s; Script and shader interface
/// declarations as <field>s.
#include <string>

#include "lodforge/scene/node.h"

namespace lodforge::vrml97 {

/// The scene as an X3D XML document. Throws DataError if the header is not
/// an X3D one, or a PROTO's text cannot be read (the message names it).
std::string write_x3d_xml(const scene::Scene& scene);

/// Writes the document to `path` ("-" = standard output) through a temporary
/// file renamed into place (".gz": gzip-compressed). Throws DataError; on an
/// error nothing is written.
void write_x3d_xml_file(const scene::Scene& scene, const std::string& path);

}  // namespace lodforge::vrml97
