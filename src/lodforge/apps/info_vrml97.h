#pragma once
/// `lodforge info` and the one-surface commands (render, compare, simplify)
/// for VRML97 and X3D classic scenes: the scene read and flattened into one
/// world-space mesh (lod/flatten_vrml97.h).
#include <nlohmann/json.hpp>
#include <string>

#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/lod/flatten_vrml97.h"

namespace lodforge::apps {

/// Bounds as `info --json` gives them: {min, max, diagonal}, or null when empty.
nlohmann::ordered_json bounds_json(const Box3& bounds);

/// The scene at `path` (VRML97, X3D classic, or X3D XML when the name says
/// .x3d, .x3d.gz or .x3dz; gzip allowed; a glTF file, by its name, as the
/// VRML97 scene gltf::gltf_to_vrml97 makes of it). Throws
/// ParseError / DataError.
vrml97::ReadResult read_vrml97_input(const std::string& path);

/// `scene` (read from `path`) flattened; the reader's and the flattening's
/// warnings, and what was not drawn, on stderr unless `quiet`.
FlatVrml97 flatten_vrml97_input(const vrml97::ReadResult& scene, const std::string& path,
                                const FlattenVrml97Options& options, bool quiet);

/// read_vrml97_input, then flatten_vrml97_input.
FlatVrml97 load_vrml97(const std::string& path, const FlattenVrml97Options& options, bool quiet);

/// The number of LOD levels of `scene`: the most levels of any LOD node (1
/// if there is none).
std::size_t vrml97_lod_level_count(const scene::Scene& scene);

/// Prints node counts per type, geometry counts per type, shapes drawn,
/// triangles, vertices and bounds (text on stdout, or JSON with `json`).
/// Returns the exit code. Throws ParseError / DataError for a bad file.
int print_vrml97_info(const std::string& path, bool json, bool quiet);

}  // namespace lodforge::apps
