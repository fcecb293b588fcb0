#pragma once
/// Geometry for the commands that work on one surface (render, compare,
/// simplify): a mesh file as it is, or a VRML 1.0 scene flattened to one mesh
/// in world space (one LOD level of it).
#include <string>
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/scene/node.h"

namespace lodforge::apps {

/// True if the path names a VRML file (.wrl, .wrl.gz, .vrml; any case).
bool is_vrml_path(const std::string& path);

/// Reads a mesh file, or a VRML scene flattened at LOD level `lod_level`
/// (warnings on stderr unless `quiet`). Throws DataError.
TriangleMesh load_geometry(const std::string& path, int lod_level = 0, bool quiet = false);

/// The LOD levels of a scene: the number of levels (the most children of any
/// LOD node; 1 if there is none) and the switch distances of the LOD node with
/// the most levels (its `range`).
struct SceneLevels {
  std::size_t count = 1;
  std::vector<float> ranges;
};
SceneLevels scene_levels(const scene::Scene& scene);

}  // namespace lodforge::apps
