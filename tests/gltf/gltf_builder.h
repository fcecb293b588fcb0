#pragma once
// Small glTF models built in memory for tests: accessors over one buffer.
#include <cstring>
#include <vector>

#include <tiny_gltf.h>

namespace lodforge::testing {

// Appends `values` as a new buffer view and accessor of `type` (FLOAT
// components, or UNSIGNED_INT for indices when `indices`); returns its index.
template <typename T>
int add_accessor(tinygltf::Model& m, const std::vector<T>& values, int type, int component_type) {
  if (m.buffers.empty()) m.buffers.emplace_back();
  auto& data = m.buffers[0].data;
  data.resize((data.size() + 3) / 4 * 4);
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = data.size();
  v.byteLength = values.size() * sizeof(T);
  data.resize(data.size() + v.byteLength);
  std::memcpy(data.data() + v.byteOffset, values.data(), v.byteLength);
  m.bufferViews.push_back(v);
  tinygltf::Accessor a;
  a.bufferView = int(m.bufferViews.size() - 1);
  a.componentType = component_type;
  a.type = type;
  a.count = values.size() / std::size_t(tinygltf::GetNumComponentsInType(std::uint32_t(type)));
  m.accessors.push_back(a);
  return int(m.accessors.size() - 1);
}

inline int add_floats(tinygltf::Model& m, const std::vector<float>& v, int type) {
  return add_accessor(m, v, type, TINYGLTF_COMPONENT_TYPE_FLOAT);
}

inline int add_indices(tinygltf::Model& m, const std::vector<std::uint32_t>& v) {
  return add_accessor(m, v, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
}

}  // namespace lodforge::testing
