#pragma once
/// Which texture coordinates a glTF texture reference reads, and how its
/// KHR_texture_transform maps them.
#include <tiny_gltf.h>

#include "lodforge/core/math.h"

namespace lodforge::gltf {

/// The affine map of KHR_texture_transform (translation x rotation x scale:
/// u' = a u + b v + c, v' = d u + e v + f) and the coordinate set it reads
/// (its own texCoord, else the reference's).
struct TextureTransform {
  int set = 0;
  double a = 1, b = 0, c = 0, d = 0, e = 1, f = 0;
  Vec2 apply(double u, double v) const {
    return {float(a * u + b * v + c), float(d * u + e * v + f)};
  }
};

/// The transform of a texture reference with `tex_coord` and `extensions`
/// (any TextureInfo kind); the identity on `tex_coord` without the extension.
/// Missing or malformed members take the extension's defaults.
TextureTransform texture_transform(int tex_coord, const tinygltf::ExtensionMap& extensions);

}  // namespace lodforge::gltf
