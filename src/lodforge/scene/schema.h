#pragma once
/// The VRML 1.0 node types: their fields with types and specification
/// defaults, the enum and bit-mask names each field takes, and which nodes are
/// groups. Readers use it to type fields; traversals use it for defaults.
///
/// The Open Inventor 2.1 nodes that change what a scene draws (Complexity,
/// RotationXYZ, Array, MultipleCopy, LevelOfDetail, VertexProperty, BaseColor,
/// PackedColor, ResetTransform, the strip, quad-mesh and face-set shapes, ...)
/// and the Inventor fields of the nodes both have (a shape's vertexProperty,
/// Separator's caching flags, ...) are in the same catalogue, marked
/// `inventor`: a reader uses them only for files with an Inventor header (in a
/// VRML 1.0 file they stay unknown nodes and fields, kept verbatim).
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lodforge/scene/node.h"

namespace lodforge::scene {

struct FieldSpec {
  std::string name;
  FieldType type;
  FieldValue default_value;
  std::vector<std::string> enum_names;  ///< allowed names for Enum/BitMask fields
  bool inventor = false;                ///< an Open Inventor field, not in VRML 1.0
};

struct NodeSpec {
  std::string type;
  bool group = false;      ///< has children
  bool separator = false;  ///< saves and restores the traversal state
  std::vector<FieldSpec> fields;
  bool inventor = false;  ///< an Open Inventor node type, not in VRML 1.0
  /// The field `name`, or nullptr; Inventor-only fields only when `inventor`.
  const FieldSpec* field(std::string_view name, bool inventor = true) const;
};

/// The spec of a standard node type, or nullptr if the type is not standard.
/// Inventor-only types are found unless `inventor` is false.
const NodeSpec* find_node_spec(std::string_view type, bool inventor = true);
/// All standard node types: VRML 1.0's in the order of its specification, then
/// the Inventor-only ones.
std::span<const NodeSpec> node_specs();

/// The value of a field of `node`: as given, else the default of its type's
/// spec. Returns nullptr only if neither exists.
const FieldValue* field_or_default(const Node& node, std::string_view name);

}  // namespace lodforge::scene
