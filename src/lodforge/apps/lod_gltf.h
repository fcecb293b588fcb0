#pragma once
/// `lodforge lod` and `format` for glTF scenes: read a `.gltf`/`.glb`, run
/// gltf_lod (lod/gltf_lod.h) or not, write `.gltf` or `.glb`.
#include <string>

#include "lodforge/core/log.h"
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

/// `format` of a glTF scene: `input` read and written back to `output`, in the
/// encoding chosen as by lod_gltf_file (a `.gltf` gets its buffer embedded;
/// external images keep their files, their URIs rewritten from the output's
/// folder). Reader warnings go to `log`. Throws DataError as lod_gltf_file.
void format_gltf_file(const std::string& input, const std::string& output,
                      const std::string& format, Log& log);

}  // namespace lodforge::apps
