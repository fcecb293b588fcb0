#include "lodforge/io/gltf/node_matrices.h"

namespace lodforge::gltf {

Mat4 local_matrix(const tinygltf::Node& node) {
  Mat4 m;
  if (node.matrix.size() == 16) {
    // glTF stores matrices column by column.
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        m.m[std::size_t(r)][std::size_t(c)] = float(node.matrix[std::size_t(c * 4 + r)]);
    return m;
  }
  if (node.translation.size() == 3)
    m = Mat4::translation(
        {float(node.translation[0]), float(node.translation[1]), float(node.translation[2])});
  if (node.rotation.size() == 4) {
    const double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2],
                 w = node.rotation[3];
    Mat4 r;
    r.m[0] = {float(1 - 2 * (y * y + z * z)), float(2 * (x * y - z * w)),
              float(2 * (x * z + y * w)), 0};
    r.m[1] = {float(2 * (x * y + z * w)), float(1 - 2 * (x * x + z * z)),
              float(2 * (y * z - x * w)), 0};
    r.m[2] = {float(2 * (x * z - y * w)), float(2 * (y * z + x * w)),
              float(1 - 2 * (x * x + y * y)), 0};
    m = m * r;
  }
  if (node.scale.size() == 3)
    m = m * Mat4::scale({float(node.scale[0]), float(node.scale[1]), float(node.scale[2])});
  return m;
}

std::vector<int> shown_roots(const tinygltf::Model& model, int scene) {
  if (scene < 0) scene = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (std::size_t(scene) < model.scenes.size()) return model.scenes[std::size_t(scene)].nodes;
  std::vector<char> child(model.nodes.size(), 0);
  for (const auto& n : model.nodes)
    for (int c : n.children) child[std::size_t(c)] = 1;
  std::vector<int> roots;
  for (std::size_t i = 0; i < model.nodes.size(); ++i)
    if (!child[i]) roots.push_back(int(i));
  return roots;
}

std::vector<NodePlacement> node_placements(const tinygltf::Model& model, int scene) {
  std::vector<NodePlacement> out(model.nodes.size());
  const std::vector<int> roots = shown_roots(model, scene);
  // Nodes form trees (read_gltf checks it), so an explicit stack visits each once.
  std::vector<std::pair<int, Mat4>> stack;
  for (int r : roots) stack.emplace_back(r, Mat4{});
  while (!stack.empty()) {
    auto [i, parent] = stack.back();
    stack.pop_back();
    auto& p = out[std::size_t(i)];
    if (p.in_scene) continue;  // a root listed twice
    p.in_scene = true;
    p.world = parent * local_matrix(model.nodes[std::size_t(i)]);
    for (int c : model.nodes[std::size_t(i)].children) stack.emplace_back(c, p.world);
  }
  return out;
}

}  // namespace lodforge::gltf
