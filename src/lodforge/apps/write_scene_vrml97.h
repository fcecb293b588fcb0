#pragma once
/// A VRML 1.0 / Inventor scene written as VRML97 or X3D by `lod` and
/// `format` (--format vrml97, x3dv or x3d, or an output named .x3dv / .x3d).
#include <string>

#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/scene/node.h"

namespace lodforge::apps {

/// The VRML97-family encoding `format` asks for a VRML 1.0 / Inventor input
/// written to `target`: "vrml97", "x3dv", "x3d", or empty when it is written
/// in its own language or as glTF (empty `format` and no .x3dv / .x3d name).
std::string vrml97_format_of(const std::string& format, const std::string& target);

/// Converts `scene` (vrml97::vrml1_to_vrml97) and writes it atomically to
/// `target` in `encoding` (vrml97_format_of: "vrml97", "x3dv" or "x3d").
/// Laid out by `write` (but X3D XML). Conversion warnings go to stderr unless
/// `quiet`. Throws DataError.
void write_scene_vrml97(const scene::Scene& scene, const std::string& target,
                        const std::string& encoding, bool quiet,
                        const vrml1::WriteOptions& write = {});

}  // namespace lodforge::apps
