#pragma once
/// A VRML 1.0 / Inventor scene written as VRML97 or X3D classic by `lod` and
/// `format` (--format vrml97 or x3dv, or an output named .x3dv).
#include <string>

#include "lodforge/scene/node.h"

namespace lodforge::apps {

/// The VRML97-family encoding `format` asks for a VRML 1.0 / Inventor input
/// written to `target`: "vrml97", "x3dv", or empty when it is written in its
/// own language or as glTF (empty `format` and no .x3dv / .x3dv.gz name).
/// Throws DataError for "x3d" (the XML encoding is not written from VRML 1.0).
std::string vrml97_format_of(const std::string& format, const std::string& target);

/// Converts `scene` (vrml97::vrml1_to_vrml97) and writes it atomically to
/// `target` as VRML97 (`x3d` false) or X3D classic. Conversion warnings go to
/// stderr unless `quiet`. Throws DataError.
void write_scene_vrml97(const scene::Scene& scene, const std::string& target, bool x3d, bool quiet);

}  // namespace lodforge::apps
