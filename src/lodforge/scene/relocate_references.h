#pragma once
/// File references of a scene that are relative to the folder of the file
/// they were read from, made relative to the folder the scene is written to,
/// so a scene written elsewhere still finds its textures and inlined files.
/// The references: VRML 1.0's Texture2 filename, WWWInline name and
/// WWWAnchor name; VRML97's and X3D's string fields named `url` or ending in
/// `Url` (ImageTexture, Inline, Anchor, AudioClip, Script, Background's
/// backUrl ...), every value of each, a `#name` after a path kept. URLs (with
/// a scheme, such as `http:` or a script's `ecmascript:`), absolute paths,
/// names of the same file (`#name`), empty names and values spanning lines
/// (program code) are left as they are; so are the texts of PROTO bodies
/// and EXTERNPROTO statements, which are kept verbatim.
#include <cstddef>
#include <filesystem>

#include "lodforge/scene/node.h"

namespace lodforge::scene {

struct RelocateResult {
  std::size_t rewritten = 0;  ///< references changed (each shared node once)
};

/// Rewrites the references of `scene` in place from `from_dir` (the input's
/// folder) to `to_dir` (the output's). Nothing changes when both are the
/// same folder.
RelocateResult relocate_references(Scene& scene, const std::filesystem::path& from_dir,
                                   const std::filesystem::path& to_dir);

}  // namespace lodforge::scene
