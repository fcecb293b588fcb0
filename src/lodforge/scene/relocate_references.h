#pragma once
/// File references of a scene (Texture2 filename, WWWInline name) that are
/// relative to the folder of the file they were read from, made relative to
/// the folder the scene is written to, so a scene written elsewhere still
/// finds its textures and inlined files. URLs (with a scheme), absolute paths
/// and empty names are left as they are.
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
