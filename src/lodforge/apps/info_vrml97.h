#pragma once
/// `lodforge info` and the one-surface commands (render, compare, simplify)
/// for VRML97 and X3D classic scenes: the scene read and flattened into one
/// world-space mesh (lod/flatten_vrml97.h).
#include <nlohmann/json.hpp>
#include <string>

#include "lodforge/lod/flatten_vrml97.h"

namespace lodforge::apps {

/// Bounds as `info --json` gives them: {min, max, diagonal}, or null when empty.
nlohmann::ordered_json bounds_json(const Box3& bounds);

/// The scene at `path` (VRML97 or X3D classic; gzip allowed) flattened at
/// `lod_level`; the reader's and the flattening's warnings, and what was
/// not drawn, on stderr unless `quiet`. Throws ParseError / DataError.
FlatVrml97 load_vrml97(const std::string& path, const FlattenVrml97Options& options, bool quiet);

/// The first Viewpoint's fieldOfView in the scene at `path` (π/4 if none).
float vrml97_field_of_view(const std::string& path);

/// The number of LOD levels of the scene at `path`: the most levels of any
/// LOD node (1 if there is none). Throws ParseError / DataError.
std::size_t vrml97_lod_level_count(const std::string& path);

/// Prints node counts per type, geometry counts per type, shapes drawn,
/// triangles, vertices and bounds (text on stdout, or JSON with `json`).
/// Returns the exit code. Throws ParseError / DataError for a bad file.
int print_vrml97_info(const std::string& path, bool json, bool quiet);

}  // namespace lodforge::apps
