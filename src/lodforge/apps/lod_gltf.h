#pragma once
/// `lodforge lod` for glTF scenes: read a `.gltf`/`.glb`, run gltf_lod, write
/// `.gltf` or `.glb` (lod/gltf_lod.h).
#include <string>

#include "lodforge/lod/generate_lod.h"

namespace lodforge::apps {

/// True if `input` is read as glTF by `lod`: by its name (.gltf, .glb).
bool is_gltf_input(const std::string& input);

/// Reads `input`, makes its levels and writes `output` as GLB when `format`
/// is "glb", as JSON glTF when it is "gltf", else by the output's name
/// (.glb / .gltf), else as the input was. Reader warnings and the pipeline's
/// log are returned in the result's log (reader warnings first). Throws
/// DataError for a bad input or an output format that is not glTF.
LodResult lod_gltf_file(const std::string& input, const std::string& output,
                        const std::string& format, const LodOptions& options);

}  // namespace lodforge::apps
