#pragma once
/// A whole scene as one triangle mesh in world space: every shape met by the
/// traversal (each USE again, in its own place), primitives tessellated.
/// Used where a scene is measured or simplified as a single surface.
#include <optional>

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

/// Throws DataError as shape_mesh does.
TriangleMesh flatten_scene(const Scene& scene, const FlattenOptions& options = {},
                           Log* log = nullptr);

}  // namespace lodforge::scene
