#pragma once
/// The VRML 1.0 node types: their fields with types and specification
/// defaults, the enum and bit-mask names each field takes, and which nodes are
/// groups. Readers use it to type fields; traversals use it for defaults.
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
};

struct NodeSpec {
  std::string type;
  bool group = false;      ///< has children
  bool separator = false;  ///< saves and restores the traversal state
  std::vector<FieldSpec> fields;
  const FieldSpec* field(std::string_view name) const;
};

/// The spec of a standard node type, or nullptr if the type is not standard.
const NodeSpec* find_node_spec(std::string_view type);
/// All standard node types, in the order of the VRML 1.0 specification.
std::span<const NodeSpec> node_specs();

/// The value of a field of `node`: as given, else the default of its type's
/// spec. Returns nullptr only if neither exists.
const FieldValue* field_or_default(const Node& node, std::string_view name);

}  // namespace lodforge::scene
