#include "lodforge/scene/flatten_scene.h"

#include <unordered_map>

#include "lodforge/scene/schema.h"

namespace lodforge::scene {
namespace {

SceneTexture scene_texture(const Node& texture2) {
  SceneTexture t;
  t.line = texture2.first_line;
  const FieldValue* name = texture2.applied_value("filename");
  if (name && !name->strings.empty()) t.filename = name->strings[0];
  if (t.filename.empty())
    if (const FieldValue* image = texture2.applied_value("image")) t.image = image->ints;
  const auto repeats = [&](const char* field) {
    const FieldValue* v = texture2.applied_value(field);
    return !v || v->strings.empty() || v->strings[0] != "CLAMP";
  };
  t.repeat_s = repeats("wrapS");
  t.repeat_t = repeats("wrapT");
  return t;
}

// Appends `part` to `all`; with appearance, its colours, texture coordinates
// (zero where it has none), opacity and the texture index of its triangles.
void append(FlatScene& all, ShapeSurface part, bool appearance, std::uint32_t texture) {
  TriangleMesh& m = all.mesh;
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  const std::size_t n = part.mesh.positions.size();
  m.positions.insert(m.positions.end(), part.mesh.positions.begin(), part.mesh.positions.end());
  for (const auto& t : part.mesh.triangles)
    m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  for (const auto& l : part.mesh.lines) m.lines.push_back({l[0] + base, l[1] + base});
  if (!appearance) return;
  m.colors.insert(m.colors.end(), part.mesh.colors.begin(), part.mesh.colors.end());
  all.opacity.insert(all.opacity.end(), part.opacity.begin(), part.opacity.end());
  if (part.mesh.has_texcoords())
    m.texcoords.insert(m.texcoords.end(), part.mesh.texcoords.begin(), part.mesh.texcoords.end());
  else
    m.texcoords.resize(m.texcoords.size() + n);
  m.materials.resize(m.triangles.size(), texture);
}

FlatScene flatten(const Scene& scene, const FlattenOptions& options, Log* log, bool appearance) {
  FlatScene all;
  bool dressed = false;  // some shape has a Material or a Texture2
  std::unordered_map<const Node*, std::uint32_t> texture_index;
  ShapeMeshOptions shape = options.shape;
  shape.appearance = appearance;
  traverse(scene,
           [&](const ShapeVisit& v) {
             ShapeSurface part = appearance ? shape_surface(v, shape, log)
                                            : ShapeSurface{.mesh = shape_mesh(v, shape, log)};
             dressed = dressed || v.state.material || part.texture;
             std::uint32_t texture = kUntextured;
             if (part.texture) {
               auto [it, fresh] = texture_index.try_emplace(
                   part.texture, static_cast<std::uint32_t>(all.textures.size()));
               if (fresh) all.textures.push_back(scene_texture(*part.texture));
               texture = it->second;
             }
             append(all, std::move(part), appearance, texture);
           },
           {.lod_level = options.lod_level, .viewpoint = options.viewpoint});
  if (appearance && !dressed) {
    all.mesh.colors.clear();
    all.mesh.texcoords.clear();
    all.mesh.materials.clear();
    all.opacity.clear();
  }
  return all;
}

}  // namespace

TriangleMesh flatten_scene(const Scene& scene, const FlattenOptions& options, Log* log) {
  return flatten(scene, options, log, false).mesh;
}

FlatScene flatten_scene_appearance(const Scene& scene, const FlattenOptions& options, Log* log) {
  return flatten(scene, options, log, true);
}

}  // namespace lodforge::scene
