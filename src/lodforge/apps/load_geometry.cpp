#include "lodforge/apps/load_geometry.h"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <unordered_set>

#include "lodforge/apps/common_options.h"
#include "lodforge/apps/info_vrml97.h"
#include "lodforge/apps/lod_vrml97.h"
#include "lodforge/core/file_io.h"
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/io/gltf/scene_mesh.h"
#include "lodforge/mesh/coordinate_range.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/scene/flatten_scene.h"

namespace lodforge::apps {

bool is_scene_path(const std::string& path) {
  std::string p = path;
  std::transform(p.begin(), p.end(), p.begin(), [](unsigned char c) { return std::tolower(c); });
  if (p.ends_with(".gz")) p.resize(p.size() - 3);
  return p.ends_with(".wrl") || p.ends_with(".vrml") || p.ends_with(".iv");
}

bool has_scene_header(std::string_view data) {
  return data.starts_with("#VRML") || data.starts_with("#Inventor");
}

namespace {

// A glTF file read, its warnings on stderr unless `quiet`.
gltf::GltfReadResult read_gltf_reported(const std::string& path, bool quiet) {
  gltf::GltfReadResult g = gltf::read_gltf_file(path);
  if (!quiet)
    for (const auto& w : g.warnings) fmt::print(stderr, "warning: {}: {}\n", path, w);
  return g;
}

// A glTF scene's mesh (gltf::scene_mesh) with its base-colour textures when
// it has its appearance, checked against the coordinate range.
scene::FlatScene gltf_drawing(const tinygltf::Model& model, TriangleMesh mesh,
                              const std::string& name) {
  check_coordinate_range(mesh, name);
  scene::FlatScene flat{.mesh = std::move(mesh)};
  if (flat.mesh.has_materials()) flat.textures = gltf::drawn_textures(model, flat.mesh);
  return flat;
}

// A mesh file as it is, or a scene flattened at `lod_level` (with its
// appearance when asked), checked against the coordinate range.
scene::FlatScene load(const std::string& path, int lod_level, const SceneReadSettings& read,
                      bool appearance) {
  const std::string name = path == "-" ? "<stdin>" : path;
  auto mesh_checked = [&](TriangleMesh m) {
    check_coordinate_range(m, name);
    return scene::FlatScene{.mesh = std::move(m)};
  };
  if (gltf::is_gltf_path(path)) {
    // A glTF scene: its triangles in world space, with the materials' base
    // colours and textures when drawn.
    const gltf::GltfReadResult g = read_gltf_reported(path, read.quiet);
    return gltf_drawing(g.scene.model, gltf::scene_mesh(g.scene.model, lod_level, appearance),
                        name);
  }
  if (is_vrml97_input(path)) {
    // A VRML97 / X3D classic scene: its shapes in world space, with their
    // materials' colours.
    scene::FlatScene flat = load_vrml97(path, {.lod_level = lod_level}, read.quiet).flat;
    check_coordinate_range(flat.mesh, name);
    if (!appearance) {  // the surface alone, as for the other scene kinds
      flat.mesh.colors.clear();
      flat.mesh.texcoords.clear();
      flat.mesh.materials.clear();
      return scene::FlatScene{.mesh = std::move(flat.mesh)};
    }
    return flat;
  }
  vrml1::ReadResult r;
  if (is_scene_path(path)) {
    r = read_scene(path, read);
  } else if (format_from_path(path) != MeshFormat::kAuto) {
    return mesh_checked(read_mesh(path));
  } else {
    // No extension to go by: the content tells (read once: it may be stdin).
    const std::string data = read_file(path);
    if (!has_scene_header(data)) return mesh_checked(read_mesh_data(data, MeshFormat::kAuto, path));
    r = read_scene_data(data, path, read);
  }
  Log log;
  scene::FlatScene flat;
  if (appearance)
    flat = scene::flatten_scene_appearance(r.scene, {.lod_level = lod_level}, &log);
  else
    flat.mesh = scene::flatten_scene(r.scene, {.lod_level = lod_level}, &log);
  if (!read.quiet) {
    std::vector<Diagnostic> warnings;
    for (const auto& d : log.entries())
      if (d.level != LogLevel::kMessage) warnings.push_back(d);
    print_diagnostics(warnings);
  }
  check_coordinate_range(flat.mesh, name);
  return flat;
}

}  // namespace

TriangleMesh load_geometry(const std::string& path, int lod_level, const SceneReadSettings& read) {
  return load(path, lod_level, read, false).mesh;
}

scene::FlatScene load_drawing(const std::string& path, int lod_level,
                              const SceneReadSettings& read) {
  return load(path, lod_level, read, true);
}

std::vector<scene::FlatScene> load_gltf_levels(const std::string& path,
                                               const SceneReadSettings& read) {
  const gltf::GltfReadResult g = read_gltf_reported(path, read.quiet);
  std::vector<scene::FlatScene> levels;
  for (std::size_t k = 0, n = gltf::lod_level_count(g.scene.model); k < n; ++k)
    levels.push_back(
        gltf_drawing(g.scene.model, gltf::scene_mesh(g.scene.model, int(k), true), path));
  return levels;
}

GltfViews load_gltf_views(const std::string& path, const SceneReadSettings& read) {
  auto g = std::make_shared<const gltf::GltfReadResult>(read_gltf_reported(path, read.quiet));
  GltfViews views{.height_angle = float(kPi / 4)};
  for (const tinygltf::Camera& c : g->scene.model.cameras)
    if (c.type == "perspective" && c.perspective.yfov > 0) {
      views.height_angle = float(c.perspective.yfov);
      break;
    }
  views.draw = [g, path, angle = views.height_angle](std::optional<Vec3> eye) {
    const tinygltf::Model& model = g->scene.model;
    return gltf_drawing(
        model,
        eye ? gltf::scene_mesh_seen_from(model, {.eye = *eye, .height_angle = angle}, true)
            : gltf::scene_mesh(model, 0, true),
        path);
  };
  return views;
}

}  // namespace lodforge::apps
