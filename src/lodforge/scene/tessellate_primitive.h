#pragma once
/// Triangle meshes of the VRML 1.0 primitives (Cube, Sphere, Cone, Cylinder)
/// in their local coordinates, with per-vertex normals and texture
/// coordinates laid out as the VRML 1.0 specification describes.
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/scene/node.h"

namespace lodforge::scene {

struct TessellateOptions {
  /// Segments around the axis (Sphere, Cone, Cylinder); Sphere uses half as
  /// many rings. At least 3; 0: segments_for_complexity(complexity).
  int segments = 0;
  /// Open Inventor's Complexity value (0..1) the segments follow when
  /// `segments` is 0; 0.5, the default, is the tessellation of a scene
  /// without Complexity (VRML 1.0 has none).
  float complexity = 0.5f;
};

/// Segments around the axis for a Complexity value: linear in it, as
/// Inventor's primitives are, 24 at the default 0.5, 4 at 0 and 48 at 1
/// (values outside 0..1 are clamped).
int segments_for_complexity(float complexity);

/// The segments `options` asks for.
int segments_of(const TessellateOptions& options);

/// Tessellates a Cube, Sphere, Cone or Cylinder node (fields or their spec
/// defaults; Cone and Cylinder honour `parts`; a negative size counts as its
/// absolute value, as real files have them). Throws DataError naming the node
/// for any other type or a size that is not finite.
TriangleMesh tessellate_primitive(const Node& node, const TessellateOptions& options = {});

}  // namespace lodforge::scene
