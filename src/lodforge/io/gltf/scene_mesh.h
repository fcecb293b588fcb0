#pragma once
/// What a glTF scene draws, as one TriangleMesh in world coordinates: every
/// triangle and line segment of every primitive of every mesh of the shown
/// scene's nodes (node_placements), once per node that uses the mesh.
#include <tiny_gltf.h>

#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge::gltf {

/// Positions, triangles and lines only (no attributes). Throws DataError as
/// primitive_mesh.
TriangleMesh scene_mesh(const tinygltf::Model& model);

}  // namespace lodforge::gltf
