#pragma once
/// VRML97 / X3D classic writer: the scene as read by read_vrml97 (fields
/// holding nodes, statements and raw values kept verbatim), in the encoding
/// its header names. The syntax of nodes, DEF/USE and values is VRML 1.0's,
/// so the VRML 1.0 writer (io/vrml1/write_vrml1.h) writes the text: numbers in
/// their shortest round-trip form, shared nodes without a name given one.
#include <string>

#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/scene/node.h"

namespace lodforge::vrml97 {

/// The scene as text. Throws DataError if scene.header is not a VRML97 or X3D
/// classic header.
std::string write_vrml97(const scene::Scene& scene);

/// Writes the scene to `path` ("-" = standard output) through a temporary
/// file renamed into place (".gz": gzip-compressed), laid out by `options`
/// (the VRML 1.0 writer's). Throws DataError.
void write_vrml97_file(const scene::Scene& scene, const std::string& path,
                       const vrml1::WriteOptions& options = {});

}  // namespace lodforge::vrml97
