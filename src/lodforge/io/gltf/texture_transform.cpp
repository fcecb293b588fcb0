#include "lodforge/io/gltf/texture_transform.h"

#include <cmath>

namespace lodforge::gltf {

TextureTransform texture_transform(int tex_coord, const tinygltf::ExtensionMap& extensions) {
  TextureTransform m{.set = tex_coord};
  const auto ext = extensions.find("KHR_texture_transform");
  if (ext == extensions.end() || !ext->second.IsObject()) return m;
  const tinygltf::Value& t = ext->second;
  auto number = [](const tinygltf::Value& v, double fallback) {
    return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
  };
  auto pair = [&](const char* key, double fallback, double& x, double& y) {
    x = y = fallback;
    const tinygltf::Value& v = t.Get(key);
    if (v.IsArray() && v.ArrayLen() == 2) {
      x = number(v.Get(0), fallback);
      y = number(v.Get(1), fallback);
    }
  };
  double ox = 0, oy = 0, sx = 1, sy = 1;
  pair("offset", 0, ox, oy);
  pair("scale", 1, sx, sy);
  const double r = number(t.Get("rotation"), 0);
  if (t.Get("texCoord").IsInt() && t.Get("texCoord").GetNumberAsInt() >= 0)
    m.set = t.Get("texCoord").GetNumberAsInt();
  m.a = std::cos(r) * sx;
  m.b = std::sin(r) * sy;
  m.c = ox;
  m.d = -std::sin(r) * sx;
  m.e = std::cos(r) * sy;
  m.f = oy;
  return m;
}

}  // namespace lodforge::gltf
