#pragma once
/// Where each glTF node is drawn: its world matrix (the product of the local
/// matrices from its root down, glTF 2.0 "Transformations": a node's
/// `matrix`, else T * R * S), for the nodes of the scene a viewer shows.
#include <vector>

#include <tiny_gltf.h>

#include "lodforge/core/math.h"

namespace lodforge::gltf {

struct NodePlacement {
  bool in_scene = false;  ///< reached from the shown scene's root nodes
  Mat4 world;             ///< identity when not in the scene
};

/// The node's own matrix.
Mat4 local_matrix(const tinygltf::Node& node);

/// The root nodes of the scene a viewer shows: `scene` if set, else the
/// default scene, else scene 0; a model without scenes shows every node
/// without a parent.
std::vector<int> shown_roots(const tinygltf::Model& model, int scene = -1);

/// One placement per node, for the scene shown_roots shows. Preconditions: the model passed
/// read_gltf's checks.
std::vector<NodePlacement> node_placements(const tinygltf::Model& model, int scene = -1);

}  // namespace lodforge::gltf
