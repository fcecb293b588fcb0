#pragma once
/// A VRML 1.0 / Inventor scene written as glTF by `lod` and `format` when the
/// output is named .glb (binary) or .gltf (JSON), optionally .gz.
#include <string>

#include "lodforge/scene/node.h"

namespace lodforge::apps {

/// Converts `scene` (gltf::scene_to_gltf) and writes it atomically to
/// `target`. Relative Texture2 file names resolve against `base_dir` and are
/// rewritten to resolve from the output's folder. `camera_angle` (radians,
/// <= 0: the scene's camera, else pi/4) sets the screen coverages of its LOD
/// nodes. `binary`: .glb, else .gltf JSON. Conversion warnings go to stderr
/// unless `quiet`. Throws DataError.
void write_scene_gltf(const scene::Scene& scene, const std::string& target,
                      const std::string& base_dir, double camera_angle, bool binary, bool quiet);

/// True if the output name asks for binary glTF (.glb, optionally .gz).
bool gltf_binary_name(const std::string& target);

}  // namespace lodforge::apps
