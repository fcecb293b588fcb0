#pragma once
/// A whole scene as one triangle mesh in world space: every shape met by the
/// traversal (each USE again, in its own place), primitives tessellated.
/// Used where a scene is measured or simplified as a single surface, and,
/// with its appearance, where it is drawn.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lodforge/core/log.h"
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/scene/node.h"
#include "lodforge/scene/shape_mesh.h"

namespace lodforge::scene {

struct FlattenOptions {
  int lod_level = 0;  ///< which child of every LOD node, without a viewpoint
  /// The eye in world space: each LOD node chooses its child by its own
  /// distance, as TraverseOptions::viewpoint says.
  std::optional<Vec3> viewpoint;
  ShapeMeshOptions shape;
};

/// Throws DataError as shape_mesh does. The mesh has no colours, texture
/// coordinates or materials (shape.appearance is ignored: see
/// flatten_scene_appearance).
TriangleMesh flatten_scene(const Scene& scene, const FlattenOptions& options = {},
                           Log* log = nullptr);

/// A Texture2 as the scene gives it; reading the image is the caller's
/// (a file name is relative to the folder of the file the node was read from).
struct SceneTexture {
  std::string filename;                ///< empty when the image is inline
  std::vector<std::int32_t> image;     ///< SFImage values: width, height, components, pixels
  std::vector<unsigned char> encoded;  ///< an image file's bytes (a glTF file's embedded image)
  bool repeat_s = true;                ///< wrapS REPEAT (else CLAMP)
  bool repeat_t = true;                ///< wrapT REPEAT (else CLAMP)
  /// The texel scales the surface colour (glTF: base colour = factor x
  /// COLOR_0 x texture) instead of replacing it (a VRML RGB texture).
  bool modulates = false;
  /// Texels of alpha below this are holes (glTF alphaMode MASK: its
  /// alphaCutoff; OPAQUE: 0, alpha ignored).
  float alpha_cutoff = 0.5f;
  int line = 0;  ///< where the Texture2 was read
};

/// Triangles of a flattened scene without a texture (FlatScene::mesh.materials).
constexpr std::uint32_t kUntextured = 0xFFFFFFFFu;

struct FlatScene {
  /// As flatten_scene, and, when some shape is under a Material or a
  /// Texture2: colors (#V, shape_surface's colours; shapes without a
  /// Material take the VRML default, diffuse 0.8 grey), texcoords (#V, (0,0)
  /// where untextured) and materials (#F: index into `textures`, or
  /// kUntextured). A scene without materials and textures gives a plain mesh.
  TriangleMesh mesh;
  std::vector<float> opacity;          ///< #V (1 - transparency) with colours, else empty
  std::vector<SceneTexture> textures;  ///< one per Texture2 node drawn, in first-use order
};

/// The scene flattened with its appearance (ShapeMeshOptions::appearance).
/// Throws DataError as shape_mesh does.
FlatScene flatten_scene_appearance(const Scene& scene, const FlattenOptions& options = {},
                                   Log* log = nullptr);

}  // namespace lodforge::scene
