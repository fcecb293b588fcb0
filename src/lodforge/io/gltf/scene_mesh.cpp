#include "lodforge/io/gltf/scene_mesh.h"

#include "lodforge/io/gltf/node_matrices.h"
#include "lodforge/io/gltf/primitive_mesh.h"

namespace lodforge::gltf {

TriangleMesh scene_mesh(const tinygltf::Model& model) {
  TriangleMesh out;
  const auto placements = node_placements(model);
  std::vector<std::vector<TriangleMesh>> meshes(model.meshes.size());
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    const int mi = model.nodes[n].mesh;
    if (mi < 0 || !placements[n].in_scene) continue;
    auto& parts = meshes[std::size_t(mi)];
    if (parts.empty())
      for (const auto& p : model.meshes[std::size_t(mi)].primitives)
        parts.push_back(primitive_mesh(model, p, mi));
    for (const auto& part : parts) {
      const auto base = std::uint32_t(out.positions.size());
      for (const auto& v : part.positions)
        out.positions.push_back(placements[n].world.transform_point(v));
      for (const auto& t : part.triangles)
        out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
      for (const auto& l : part.lines) out.lines.push_back({l[0] + base, l[1] + base});
    }
  }
  return out;
}

}  // namespace lodforge::gltf
