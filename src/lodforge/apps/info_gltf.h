#pragma once
/// `lodforge info` for glTF scenes: object counts, extensions, and per mesh
/// its nodes and per primitive its mode, vertices, triangles and material.
#include <string>

namespace lodforge::apps {

/// Prints the summary of the glTF file `path` (text on stdout, or JSON with
/// `json`; reader warnings on stderr unless `quiet`). Returns the exit code.
/// Throws DataError for a bad file.
int print_gltf_info(const std::string& path, bool json, bool quiet);

}  // namespace lodforge::apps
