#pragma once
/// Rendering traversal of a VRML 1.0 scene graph with its state: the
/// accumulated transform and the current property nodes (Coordinate3, Normal,
/// TextureCoordinate2, Material, the bindings, ShapeHints, Texture2), as the
/// VRML 1.0 specification defines them. Calls back for every shape.
///
/// Group semantics: Separator, WWWAnchor, LOD and WWWInline save and restore
/// the state; TransformSeparator saves only the transform; Group and Switch
/// pass state on. Switch follows whichChild (-1 none, -3 all, and Inventor's
/// -2: the choice of the Switch it is traversed under); LOD takes the
/// child chosen by TraverseOptions (clamped to its last child).
///
/// Open Inventor nodes (files with an Inventor header) are part of the same
/// state machine, so everything built on the traversal (info, lod, render,
/// compare) sees the same geometry:
///  - RotationXYZ rotates, ResetTransform resets the transform;
///  - Array and MultipleCopy traverse their children once per instance, each
///    under its own translation or matrix (and state saved around each, as
///    Inventor does); LevelOfDetail takes its child as LOD does;
///  - Complexity is kept in the state (complexity_value) for tessellation;
///  - BaseColor and PackedColor set the material; VertexProperty, as a node
///    or as a shape's vertexProperty field, sets the coordinates, normals,
///    texture coordinates and colours (with its bindings) it has values for.
///    Their values are seen as the VRML 1.0 nodes Coordinate3, Normal,
///    TextureCoordinate2, Material, MaterialBinding and NormalBinding that the
///    traversal makes for them (TraversalState::derived keeps them alive: a
///    visitor that keeps such pointers past its call keeps a copy of the
///    state);
///  - a property node whose every field carries the ignore flag `~` is not
///    applied, and the transform nodes take the default of an ignored field.
#include <functional>
#include <memory>
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
  /// Texture coordinates' transform (the Texture2Transform nodes met, each
  /// multiplied on the right as a Transform is; 2D in x and y).
  Mat4 texture_transform;
  const Node* font_style = nullptr;
  const Node* complexity = nullptr;  ///< Inventor Complexity; nullptr: value 0.5
  /// Inventor Switch whichChild -2 takes this (the enclosing Switch's choice).
  int switch_choice = -1;
  /// Owns the nodes the traversal made for Inventor property nodes (see the
  /// file comment); every copy of the state keeps them alive.
  std::shared_ptr<const void> derived;
};

/// The Complexity value in effect, clamped to 0..1 (Inventor's default 0.5
/// without a Complexity node).
float complexity_value(const TraversalState& state);

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
  /// The transform in effect where each path node was entered (the one a
  /// LOD node's `center` is in): path_transform[i] belongs to path[i].
  std::span<const Mat4> path_transform = {};
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
/// Translation, Rotation, Scale, Inventor's RotationXYZ); identity for any
/// other node.
Mat4 local_transform(const Node& node);

/// Walks the scene and calls `visit` for every shape met. Throws DataError
/// ("line N: ...") for an Inventor Array of more than a million instances.
void traverse(const Scene& scene, const std::function<void(const ShapeVisit&)>& visit,
              const TraverseOptions& options = {});

/// What for_each_node walks into.
struct NodeWalkOptions {
  /// Also the nodes held in node-valued fields (VRML97's children of
  /// Shape, Inventor's vertexProperty), besides children.
  bool field_nodes = false;
};

/// Calls `visit` once for every distinct node reachable from the scene's
/// roots (a node used at several places once), depth first; null entries
/// are skipped. No traversal state is kept. O(nodes).
void for_each_node(const Scene& scene, const std::function<void(const Node&)>& visit,
                   const NodeWalkOptions& options = {});

/// The number of LOD levels of a scene: the most children of any LOD (or
/// Inventor LevelOfDetail) node (1 if there is none).
std::size_t lod_level_count(const Scene& scene);

}  // namespace lodforge::scene
