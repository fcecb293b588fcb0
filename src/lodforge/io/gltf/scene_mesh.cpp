#include "lodforge/io/gltf/scene_mesh.h"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "lodforge/core/data_uri.h"
#include "lodforge/core/error.h"
#include "lodforge/io/gltf/accessor_data.h"
#include "lodforge/io/gltf/node_matrices.h"
#include "lodforge/io/gltf/primitive_mesh.h"
#include "lodforge/io/gltf/texture_transform.h"

namespace lodforge::gltf {

namespace {

// A node's MSFT_lod ids (the nodes of its levels 1..n); null without any.
const tinygltf::Value* lod_ids(const tinygltf::Node& node) {
  const auto lod = node.extensions.find("MSFT_lod");
  if (lod == node.extensions.end()) return nullptr;
  const tinygltf::Value& ids = lod->second.Get("ids");
  return ids.IsArray() && ids.ArrayLen() > 0 ? &ids : nullptr;
}

// The mesh node `n` draws at `lod_level` (MSFT_lod's ids name the levels).
int mesh_at_level(const tinygltf::Model& model, std::size_t n, int lod_level) {
  const auto& node = model.nodes[n];
  const tinygltf::Value* level_ids = lod_level > 0 ? lod_ids(node) : nullptr;
  if (!level_ids) return node.mesh;
  const tinygltf::Value& ids = *level_ids;
  const int k = std::min(lod_level, int(ids.ArrayLen())) - 1;
  const int id = ids.Get(k).IsNumber() ? ids.Get(k).GetNumberAsInt() : -1;
  if (id < 0 || std::size_t(id) >= model.nodes.size() || model.nodes[std::size_t(id)].mesh < 0)
    throw DataError(fmt::format("node {}: MSFT_lod id {} is not a node with a mesh", n, id));
  return model.nodes[std::size_t(id)].mesh;
}

}  // namespace

void add_colors(const tinygltf::Model& model, const tinygltf::Primitive& p, TriangleMesh& part) {
  Vec3 base{1, 1, 1};
  if (p.material >= 0 && std::size_t(p.material) < model.materials.size()) {
    const auto& f = model.materials[std::size_t(p.material)].pbrMetallicRoughness.baseColorFactor;
    if (f.size() >= 3) base = {float(f[0]), float(f[1]), float(f[2])};
  }
  part.colors.assign(part.positions.size(), base);
  const auto color = p.attributes.find("COLOR_0");
  if (color == p.attributes.end()) return;
  const AccessorValues c = read_accessor(model, color->second);
  if (c.components < 3 || c.count != part.positions.size()) return;
  for (std::size_t i = 0; i < c.count; ++i)
    part.colors[i] = {base.x * float(c.values[i * std::size_t(c.components)]),
                      base.y * float(c.values[i * std::size_t(c.components) + 1]),
                      base.z * float(c.values[i * std::size_t(c.components) + 2])};
}

const tinygltf::TextureInfo* base_color_texture(const tinygltf::Model& model, int m) {
  if (m < 0 || std::size_t(m) >= model.materials.size()) return nullptr;
  const auto& info = model.materials[std::size_t(m)].pbrMetallicRoughness.baseColorTexture;
  if (info.index < 0 || std::size_t(info.index) >= model.textures.size()) return nullptr;
  return &info;
}

void add_texture(const tinygltf::Model& model, const tinygltf::Primitive& p, TriangleMesh& part) {
  part.texcoords.assign(part.positions.size(), Vec2{});
  part.materials.assign(part.triangles.size(), scene::kUntextured);
  const tinygltf::TextureInfo* info = base_color_texture(model, p.material);
  if (!info) return;
  const TextureTransform m = texture_transform(info->texCoord, info->extensions);
  const auto uv = p.attributes.find(fmt::format("TEXCOORD_{}", m.set));
  if (uv == p.attributes.end()) return;
  const AccessorValues t = read_accessor(model, uv->second);
  if (t.components != 2 || t.count != part.positions.size()) return;
  for (std::size_t i = 0; i < t.count; ++i) {
    const Vec2 uv = m.apply(t.values[2 * i], t.values[2 * i + 1]);
    part.texcoords[i] = {uv.x, 1 - uv.y};
  }
  part.materials.assign(part.triangles.size(), std::uint32_t(p.material));
}

std::size_t lod_level_count(const tinygltf::Model& model) {
  std::size_t most = 0;
  for (const auto& node : model.nodes)
    if (const tinygltf::Value* ids = lod_ids(node)) most = std::max(most, ids->ArrayLen());
  return 1 + most;
}

namespace {

// Every node's mesh as `mesh_of(n)` chooses it (< 0: nothing), in world
// space, in one mesh.
template <class MeshOf>
TriangleMesh gather(const tinygltf::Model& model, const std::vector<NodePlacement>& placements,
                    MeshOf mesh_of, bool colors) {
  TriangleMesh out;
  std::vector<std::vector<TriangleMesh>> meshes(model.meshes.size());
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    if (!placements[n].in_scene) continue;
    const int mi = mesh_of(n);
    if (mi < 0) continue;
    auto& parts = meshes[std::size_t(mi)];
    if (parts.empty())
      for (const auto& p : model.meshes[std::size_t(mi)].primitives) {
        parts.push_back(primitive_mesh(model, p, mi));
        if (colors) {
          add_colors(model, p, parts.back());
          add_texture(model, p, parts.back());
        }
      }
    for (const auto& part : parts) {
      const auto base = std::uint32_t(out.positions.size());
      for (const auto& v : part.positions)
        out.positions.push_back(placements[n].world.transform_point(v));
      for (const auto& t : part.triangles)
        out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
      for (const auto& l : part.lines) out.lines.push_back({l[0] + base, l[1] + base});
      out.colors.insert(out.colors.end(), part.colors.begin(), part.colors.end());
      out.texcoords.insert(out.texcoords.end(), part.texcoords.begin(), part.texcoords.end());
      out.materials.insert(out.materials.end(), part.materials.begin(), part.materials.end());
    }
  }
  return out;
}

// The bounding sphere of a mesh, as lodforge lod takes it (box_centred_sphere
// of all its primitives' positions), in the mesh's coordinates.
BoxSphere mesh_sphere(const tinygltf::Model& model, int mesh) {
  std::vector<Vec3> points;
  for (const auto& p : model.meshes[std::size_t(mesh)].primitives) {
    const TriangleMesh part = primitive_mesh(model, p, mesh);
    points.insert(points.end(), part.positions.begin(), part.positions.end());
  }
  return box_centred_sphere(points);
}

// The level node n shows at screen coverage c (-1: none), by its
// MSFT_screencoverage; `levels` simplified levels.
int level_at_coverage(const tinygltf::Node& node, int levels, double c) {
  const tinygltf::Value& cov = node.extras.Get("MSFT_screencoverage");
  if (!cov.IsArray()) return 0;
  const int n = int(cov.ArrayLen());
  for (int i = 0; i < n && i <= levels; ++i) {
    if (!cov.Get(i).IsNumber()) return 0;
    if (c > cov.Get(i).GetNumberAsDouble()) return i;
  }
  return n > levels ? -1 : levels;
}

}  // namespace

scene::SceneTexture material_texture(const tinygltf::Model& model, int m) {
  scene::SceneTexture out;
  const tinygltf::Material& material = model.materials[std::size_t(m)];
  const int t = material.pbrMetallicRoughness.baseColorTexture.index;
  out.modulates = true;
  out.alpha_cutoff = material.alphaMode == "MASK"    ? float(material.alphaCutoff)
                     : material.alphaMode == "BLEND" ? 0.5f
                                                     : 0.0f;
  const tinygltf::Texture& texture = model.textures[std::size_t(t)];
  if (texture.sampler >= 0 && std::size_t(texture.sampler) < model.samplers.size()) {
    const tinygltf::Sampler& s = model.samplers[std::size_t(texture.sampler)];
    out.repeat_s = s.wrapS != TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    out.repeat_t = s.wrapT != TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  }
  if (texture.source < 0 || std::size_t(texture.source) >= model.images.size()) return out;
  const tinygltf::Image& image = model.images[std::size_t(texture.source)];
  if (!image.image.empty()) {
    out.encoded = image.image;
  } else if (image.bufferView >= 0 && std::size_t(image.bufferView) < model.bufferViews.size()) {
    const tinygltf::BufferView& view = model.bufferViews[std::size_t(image.bufferView)];
    if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size()) return out;
    const auto& data = model.buffers[std::size_t(view.buffer)].data;
    if (view.byteOffset + view.byteLength <= data.size())
      out.encoded.assign(data.begin() + std::ptrdiff_t(view.byteOffset),
                         data.begin() + std::ptrdiff_t(view.byteOffset + view.byteLength));
  } else {
    out.filename = percent_decoded(image.uri);
  }
  return out;
}

std::vector<scene::SceneTexture> drawn_textures(const tinygltf::Model& model, TriangleMesh& mesh) {
  std::vector<scene::SceneTexture> out;
  std::map<std::uint32_t, std::uint32_t> slot;
  for (std::uint32_t& m : mesh.materials) {
    if (m == scene::kUntextured || !base_color_texture(model, int(m))) {
      m = scene::kUntextured;
      continue;
    }
    const auto [it, added] = slot.try_emplace(m, std::uint32_t(out.size()));
    if (added) out.push_back(material_texture(model, int(m)));
    m = it->second;
  }
  return out;
}

TriangleMesh scene_mesh(const tinygltf::Model& model, int lod_level, bool colors) {
  return gather(
      model, node_placements(model),
      [&](std::size_t n) { return mesh_at_level(model, n, lod_level); }, colors);
}

double screen_coverage(double radius, double distance, double height_angle) {
  const double t = std::tan(height_angle / 2);
  return distance > 0 && t > 0 ? radius / (distance * t) : std::numeric_limits<double>::infinity();
}

TriangleMesh scene_mesh_seen_from(const tinygltf::Model& model, const CoverageView& view,
                                  bool colors) {
  const auto placements = node_placements(model);
  std::vector<std::optional<BoxSphere>> spheres(model.meshes.size());  // per mesh, once
  auto mesh_of = [&](std::size_t n) {
    const tinygltf::Node& node = model.nodes[n];
    const tinygltf::Value* ids = lod_ids(node);
    if (!ids || node.mesh < 0) return mesh_at_level(model, n, 0);
    auto& sphere = spheres[std::size_t(node.mesh)];
    if (!sphere) sphere = mesh_sphere(model, node.mesh);
    const Mat4& world = placements[n].world;
    const double c = screen_coverage(
        sphere->radius * world.max_scale(),
        double(length(view.eye - world.transform_point(sphere->center))), view.height_angle);
    const int level = level_at_coverage(node, int(ids->ArrayLen()), c);
    return level < 0 ? -1 : mesh_at_level(model, n, level);
  };
  return gather(model, placements, mesh_of, colors);
}

}  // namespace lodforge::gltf
