#include "lodforge/io/gltf/primitive_mesh.h"

#include <fmt/core.h>

#include "lodforge/core/error.h"
#include "lodforge/io/gltf/accessor_data.h"

namespace lodforge::gltf {

TriangleMesh primitive_mesh(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                            int mesh_index) {
  TriangleMesh mesh;
  const auto position = primitive.attributes.find("POSITION");
  if (position == primitive.attributes.end()) return mesh;  // draws nothing
  const AccessorValues p = read_accessor(model, position->second);
  if (p.components != 3)
    throw DataError(
        fmt::format("mesh {}: POSITION has {} components, not 3", mesh_index, p.components));
  mesh.positions.resize(p.count);
  for (std::size_t i = 0; i < p.count; ++i)
    mesh.positions[i] = {float(p.values[3 * i]), float(p.values[3 * i + 1]),
                         float(p.values[3 * i + 2])};
  std::vector<std::uint32_t> index;
  if (primitive.indices >= 0) {
    const AccessorValues a = read_accessor(model, primitive.indices);
    index.reserve(a.values.size());
    for (double v : a.values) {
      if (!(v >= 0 && v < double(p.count)))
        throw DataError(
            fmt::format("mesh {}: index {} past its {} vertices", mesh_index, v, p.count));
      index.push_back(std::uint32_t(v));
    }
  } else {
    index.resize(p.count);
    for (std::size_t i = 0; i < p.count; ++i) index[i] = std::uint32_t(i);
  }
  auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (a != b && b != c && a != c) mesh.triangles.push_back({a, b, c});
  };
  const std::size_t n = index.size();
  switch (primitive.mode) {
    case TINYGLTF_MODE_TRIANGLES:
      for (std::size_t i = 0; i + 2 < n; i += 3) add(index[i], index[i + 1], index[i + 2]);
      break;
    case TINYGLTF_MODE_TRIANGLE_STRIP:
      // Triangle i is (i, i+1, i+2) for even i and (i+1, i, i+2) for odd i.
      for (std::size_t i = 0; i + 2 < n; ++i)
        if (i % 2 == 0)
          add(index[i], index[i + 1], index[i + 2]);
        else
          add(index[i + 1], index[i], index[i + 2]);
      break;
    case TINYGLTF_MODE_TRIANGLE_FAN:
      // Triangle i is (i+1, i+2, 0).
      for (std::size_t i = 0; i + 2 < n; ++i) add(index[i + 1], index[i + 2], index[0]);
      break;
    case TINYGLTF_MODE_LINE:
      for (std::size_t i = 0; i + 1 < n; i += 2) mesh.lines.push_back({index[i], index[i + 1]});
      break;
    case TINYGLTF_MODE_LINE_STRIP:
    case TINYGLTF_MODE_LINE_LOOP:
      for (std::size_t i = 0; i + 1 < n; ++i) mesh.lines.push_back({index[i], index[i + 1]});
      if (primitive.mode == TINYGLTF_MODE_LINE_LOOP && n > 2)
        mesh.lines.push_back({index[n - 1], index[0]});
      break;
    default:  // POINTS
      break;
  }
  return mesh;
}

}  // namespace lodforge::gltf
