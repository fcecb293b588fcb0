#pragma once
/// Geometry for the commands that work on one surface (render, compare,
/// simplify): a mesh file as it is, or a VRML 1.0 / Open Inventor scene
/// flattened to one mesh in world space (one LOD level of it).
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lodforge/apps/common_options.h"
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/scene/flatten_scene.h"
#include "lodforge/scene/node.h"

namespace lodforge::apps {

/// True if the path names a scene file: VRML (.wrl, .vrml) or Open Inventor
/// (.iv), optionally .gz; any case.
bool is_scene_path(const std::string& path);

/// True if `data` (a file's first bytes, decompressed) starts with a VRML or
/// Open Inventor header.
bool has_scene_header(std::string_view data);

/// Reads a mesh file, or a scene flattened at LOD level `lod_level` (warnings
/// on stderr unless `read.quiet`): a scene is a file of a scene extension, or
/// any other file but a mesh extension's (.ply, .obj, .off, .stl) with a VRML
/// or Inventor header, as `info` reads it. Throws DataError, also for
/// coordinates out of the range of check_coordinate_range.
TriangleMesh load_geometry(const std::string& path, int lod_level = 0,
                           const SceneReadSettings& read = {});

/// As load_geometry, with what the surfaces look like: a scene is flattened
/// with its appearance (scene::flatten_scene_appearance), a mesh file is
/// the mesh as it is (its vertex colours, no textures).
scene::FlatScene load_drawing(const std::string& path, int lod_level = 0,
                              const SceneReadSettings& read = {});

/// A glTF scene (read once) as load_drawing draws it at each of its levels:
/// level 0, then each MSFT_lod level (gltf::lod_level_count of them in all).
std::vector<scene::FlatScene> load_gltf_levels(const std::string& path,
                                               const SceneReadSettings& read = {});

/// A glTF scene (read once) as a viewer draws it from a camera: `draw(eye)`
/// as load_drawing draws it, with every MSFT_lod node at the level its screen
/// coverage chooses from `eye` (gltf::scene_mesh_seen_from; level 0 without
/// an eye) for a camera `height_angle` high: the first perspective camera's
/// yfov, else pi/4.
struct GltfViews {
  std::function<scene::FlatScene(std::optional<Vec3> eye)> draw;
  float height_angle = 0;
};
GltfViews load_gltf_views(const std::string& path, const SceneReadSettings& read = {});

}  // namespace lodforge::apps
