#pragma once
/// Triangle meshes of the VRML 1.0 primitives (Cube, Sphere, Cone, Cylinder)
/// in their local coordinates, with per-vertex normals and texture
/// coordinates laid out as the VRML 1.0 specification describes.
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/scene/node.h"

namespace lodforge::scene {

struct TessellateOptions {
  /// Segments around the axis (Sphere, Cone, Cylinder); Sphere uses half as
  /// many rings. At least 3.
  int segments = 24;
};

/// Tessellates a Cube, Sphere, Cone or Cylinder node (fields or their spec
/// defaults; Cone and Cylinder honour `parts`; a negative size counts as its
/// absolute value, as real files have them). Throws DataError naming the node
/// for any other type or a size that is not finite.
TriangleMesh tessellate_primitive(const Node& node, const TessellateOptions& options = {});

}  // namespace lodforge::scene
