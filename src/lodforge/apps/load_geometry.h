#pragma once
/// Geometry for the commands that work on one surface (render, compare,
/// simplify): a mesh file as it is, or a VRML 1.0 scene flattened to one mesh
/// in world space (one LOD level of it).
#include <string>
#include <vector>

#include "lodforge/apps/common_options.h"
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/scene/node.h"

namespace lodforge::apps {

/// True if the path names a VRML file (.wrl, .wrl.gz, .vrml; any case).
bool is_vrml_path(const std::string& path);

/// Reads a mesh file, or a VRML scene flattened at LOD level `lod_level`
/// (warnings on stderr unless `read.quiet`). Throws DataError, also for
/// coordinates out of the range of check_coordinate_range.
TriangleMesh load_geometry(const std::string& path, int lod_level = 0,
                           const SceneReadSettings& read = {});

/// The number of LOD levels of a scene: the most children of any LOD node (1
/// if there is none).
std::size_t lod_level_count(const scene::Scene& scene);

}  // namespace lodforge::apps
