#pragma once
/// What a glTF scene draws, as one TriangleMesh in world coordinates: every
/// triangle and line segment of every primitive of every mesh of the shown
/// scene's nodes (node_placements), once per node that uses the mesh.
#include <tiny_gltf.h>

#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge::gltf {

/// Positions, triangles and lines; with `colors`, also each vertex's colour:
/// its primitive's base colour (the material's baseColorFactor, white
/// without a material) times its COLOR_0 when it has one, RGB (textures are
/// not sampled). `lod_level` K > 0 draws, for a node with `MSFT_lod`, the
/// mesh of its level K (its coarsest level when it has fewer) in the node's
/// place. Throws DataError as primitive_mesh, or for an MSFT_lod id that is
/// not a node with a mesh.
TriangleMesh scene_mesh(const tinygltf::Model& model, int lod_level = 0, bool colors = false);

/// The levels scene_mesh can show: 1 + the most `MSFT_lod` ids of a node
/// (1 when no node has any).
std::size_t lod_level_count(const tinygltf::Model& model);

}  // namespace lodforge::gltf
