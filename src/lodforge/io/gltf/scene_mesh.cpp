#include "lodforge/io/gltf/scene_mesh.h"

#include <fmt/core.h>

#include <algorithm>

#include "lodforge/core/error.h"
#include "lodforge/io/gltf/accessor_data.h"
#include "lodforge/io/gltf/node_matrices.h"
#include "lodforge/io/gltf/primitive_mesh.h"

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

// `part` (primitive_mesh of `p`) with its vertices' colours.
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

}  // namespace

std::size_t lod_level_count(const tinygltf::Model& model) {
  std::size_t most = 0;
  for (const auto& node : model.nodes)
    if (const tinygltf::Value* ids = lod_ids(node)) most = std::max(most, ids->ArrayLen());
  return 1 + most;
}

TriangleMesh scene_mesh(const tinygltf::Model& model, int lod_level, bool colors) {
  TriangleMesh out;
  const auto placements = node_placements(model);
  std::vector<std::vector<TriangleMesh>> meshes(model.meshes.size());
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    const int mi = mesh_at_level(model, n, lod_level);
    if (mi < 0 || !placements[n].in_scene) continue;
    auto& parts = meshes[std::size_t(mi)];
    if (parts.empty())
      for (const auto& p : model.meshes[std::size_t(mi)].primitives) {
        parts.push_back(primitive_mesh(model, p, mi));
        if (colors) add_colors(model, p, parts.back());
      }
    for (const auto& part : parts) {
      const auto base = std::uint32_t(out.positions.size());
      for (const auto& v : part.positions)
        out.positions.push_back(placements[n].world.transform_point(v));
      for (const auto& t : part.triangles)
        out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
      for (const auto& l : part.lines) out.lines.push_back({l[0] + base, l[1] + base});
      out.colors.insert(out.colors.end(), part.colors.begin(), part.colors.end());
    }
  }
  return out;
}

}  // namespace lodforge::gltf
