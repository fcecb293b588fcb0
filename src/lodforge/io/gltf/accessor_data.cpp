#include "lodforge/io/gltf/accessor_data.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "lodforge/core/error.h"

namespace lodforge::gltf {
namespace {

template <typename T>
double load(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return double(v);
}

// One component at `p`, normalized as the specification's table of
// "accessor.normalized" states: c / max for unsigned, max(c / max, -1) for signed.
double component(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_DOUBLE:
      return load<double>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const double v = load<std::uint8_t>(p);
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double v = load<std::int8_t>(p);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const double v = load<std::uint16_t>(p);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const double v = load<std::int16_t>(p);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return load<std::uint32_t>(p);
    case TINYGLTF_COMPONENT_TYPE_INT:
      return load<std::int32_t>(p);
    default:
      return 0;
  }
}

const unsigned char* view_data(const tinygltf::Model& m, int view, std::size_t offset) {
  const auto& v = m.bufferViews[std::size_t(view)];
  return m.buffers[std::size_t(v.buffer)].data.data() + v.byteOffset + offset;
}

}  // namespace

AccessorValues read_accessor(const tinygltf::Model& model, int index) {
  const auto& a = model.accessors[std::size_t(index)];
  AccessorValues out;
  out.count = a.count;
  out.components = tinygltf::GetNumComponentsInType(std::uint32_t(a.type));
  const int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType));
  const std::size_t n = std::size_t(out.components);
  out.values.assign(out.count * n, 0.0);
  if (a.bufferView >= 0) {
    const std::size_t stride =
        std::size_t(a.ByteStride(model.bufferViews[std::size_t(a.bufferView)]));
    const unsigned char* base = view_data(model, a.bufferView, a.byteOffset);
    for (std::size_t i = 0; i < out.count; ++i)
      for (std::size_t c = 0; c < n; ++c)
        out.values[i * n + c] =
            component(base + i * stride + c * std::size_t(size), a.componentType, a.normalized);
  }
  if (a.sparse.isSparse) {
    const auto& s = a.sparse;
    const int index_size =
        tinygltf::GetComponentSizeInBytes(std::uint32_t(s.indices.componentType));
    const unsigned char* indices =
        view_data(model, s.indices.bufferView, std::size_t(s.indices.byteOffset));
    const unsigned char* values =
        view_data(model, s.values.bufferView, std::size_t(s.values.byteOffset));
    for (std::size_t k = 0; k < std::size_t(s.count); ++k) {
      const double target =
          component(indices + k * std::size_t(index_size), s.indices.componentType, false);
      if (!(target >= 0 && target < double(out.count)))
        throw DataError(fmt::format("accessor {}: sparse index {} is past its {} elements", index,
                                    target, out.count));
      for (std::size_t c = 0; c < n; ++c)
        out.values[std::size_t(target) * n + c] =
            component(values + (k * n + c) * std::size_t(size), a.componentType, a.normalized);
    }
  }
  return out;
}

}  // namespace lodforge::gltf
