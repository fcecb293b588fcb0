#pragma once
/// The shapes a VRML 1.0 / Inventor scene draws, in world space with their
/// appearance, grouped by the LOD node (and child of it) they are drawn
/// under: what a converter to a format without VRML 1.0's state machine
/// (glTF, VRML97) starts from.
///
/// The scene is traversed once per LOD level (scene::traverse shows one child
/// of every LOD node); each shape is taken at the traversal that shows its
/// innermost LOD's child, so every drawn shape is met once per use (a shared
/// node used twice is two shapes). A LOD inside another LOD's child is drawn
/// at the level its parent shows.
#include <map>
#include <vector>

#include "lodforge/core/log.h"
#include "lodforge/scene/shape_mesh.h"

namespace lodforge::scene {

/// One shape drawn: its world-space surface and the node it came from.
struct DrawnShape {
  ShapeSurface surface;
  const Node* node = nullptr;  ///< the shape node (IndexedFaceSet, Cube, AsciiText, ...)
};

/// The shapes drawn under one occurrence of a LOD node, per child.
struct LodGroup {
  const Node* lod = nullptr;
  Mat4 transform;  ///< the transform in effect at the LOD node (its `center` is in it)
  std::vector<std::vector<DrawnShape>> levels;  ///< one entry per child of the LOD
};

struct LodShapes {
  std::vector<DrawnShape> plain;  ///< shapes outside any LOD node
  /// Per LOD occurrence (keyed by the child indices leading to it, so each
  /// use of a shared LOD is its own), in traversal order of the keys.
  std::map<std::vector<std::size_t>, LodGroup> lods;
  const Node* camera = nullptr;  ///< the first PerspectiveCamera met, or nullptr
};

/// Collects the shapes of `scene` (shape_surface with world_space). Warnings
/// of shape_surface go to `log`. Throws the DataErrors of shape_surface.
LodShapes collect_lod_shapes(const Scene& scene, Log& log);

}  // namespace lodforge::scene
