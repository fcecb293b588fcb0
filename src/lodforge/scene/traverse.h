#pragma once
/// Rendering traversal of a VRML 1.0 scene graph with its state: the
/// accumulated transform and the current property nodes (Coordinate3, Normal,
/// TextureCoordinate2, Material, the bindings, ShapeHints, Texture2), as the
/// VRML 1.0 specification defines them. Calls back for every shape.
///
/// Group semantics: Separator, WWWAnchor, LOD and WWWInline save and restore
/// the state; TransformSeparator saves only the transform; Group and Switch
/// pass state on. Switch follows whichChild (-1 none, -3 all); LOD takes the
/// child chosen by TraverseOptions (clamped to its last child).
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "lodforge/core/math.h"
#include "lodforge/scene/node.h"

namespace lodforge::scene {

struct TraversalState {
  Mat4 transform;                     ///< object to world
  const Node* coordinate3 = nullptr;  ///< nullptr: the spec default
  const Node* normal = nullptr;
  const Node* texture_coordinate2 = nullptr;
  const Node* material = nullptr;
  const Node* material_binding = nullptr;
  const Node* normal_binding = nullptr;
  const Node* shape_hints = nullptr;
  const Node* texture2 = nullptr;
  const Node* font_style = nullptr;
};

struct ShapeVisit {
  const Node& shape;  ///< IndexedFaceSet, IndexedLineSet, PointSet, Cube, ...
  const TraversalState& state;
  const Node* camera;  ///< first PerspectiveCamera met so far, or nullptr
  /// The group nodes from a root down to the shape's parent.
  const std::vector<const Node*>& path;
  /// Where the shape is: its index in path.back()->children, or in
  /// Scene::roots when the path is empty.
  std::size_t child_index = 0;
  /// Where each path node is: path_index[i] is the index of path[i] in
  /// path[i-1]->children (path_index[0]: in Scene::roots). Tells apart two
  /// uses of one shared node by the same parent.
  std::span<const std::size_t> path_index = {};
};

struct TraverseOptions {
  int lod_level = 0;  ///< which child of each LOD node to traverse, without a viewpoint
  /// The eye in world space. When set, each LOD node chooses its child by its
  /// own distance d from the eye to its `center` (transformed to world space
  /// by the current transform), as a VRML 1.0 browser does: child 0 for
  /// d < range[0], child i for range[i-1] <= d < range[i], the last child
  /// beyond the last range; clamped to the last child. `lod_level` is ignored.
  std::optional<Vec3> viewpoint;
};

/// True for the node types the traversal reports as shapes.
bool is_shape_type(std::string_view type);

/// The local matrix of a transform node (Transform, MatrixTransform,
/// Translation, Rotation, Scale); identity for any other node.
Mat4 local_transform(const Node& node);

/// Walks the scene and calls `visit` for every shape met.
void traverse(const Scene& scene, const std::function<void(const ShapeVisit&)>& visit,
              const TraverseOptions& options = {});

}  // namespace lodforge::scene
