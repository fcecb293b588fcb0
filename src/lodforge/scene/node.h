#pragma once
/// The format-neutral scene graph: nodes with typed fields and children, shared
/// through DEF/USE. Its vocabulary is VRML 1.0's (the product's scene format);
/// nodes of other types are kept as they were read.
///
/// A node is shared when several parents hold the same NodePtr (a USE). The
/// graph is a DAG: cycles are rejected by the reader.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace lodforge::scene {

/// The base types of VRML 1.0 fields (and the Open Inventor 2.x types kNode
/// and kUInt32 after them); a field is single (SF) or multiple (MF).
enum class FieldKind : std::uint8_t {
  kBitMask,
  kBool,
  kColor,
  kEnum,
  kFloat,
  kImage,
  kLong,
  kMatrix,
  kRotation,
  kString,
  kVec2f,
  kVec3f,
  kNode,    ///< Open Inventor SFNode / MFNode (e.g. a shape's vertexProperty)
  kUInt32,  ///< Open Inventor SFUInt32 / MFUInt32 (packed colours), written in hexadecimal
};

struct FieldType {
  FieldKind kind = FieldKind::kFloat;
  bool multi = false;
  friend bool operator==(const FieldType&, const FieldType&) = default;
};

/// "SFFloat", "MFVec3f", ...
std::string type_name(FieldType type);
/// Parses a type name such as "MFVec3f"; returns false if it is none.
bool parse_type_name(std::string_view name, FieldType& out);
/// Floats per value for float kinds (Color 3, Float 1, Matrix 16, Rotation 4,
/// Vec2f 2, Vec3f 3), 0 for the others.
int float_components(FieldKind kind);

struct Node;

/// The value of a field. Which vector holds it depends on the kind:
///  - floats:  Color, Float, Matrix, Rotation, Vec2f, Vec3f (components x count, flat)
///  - ints:    Bool (0/1), Long, UInt32 (the bit pattern), Image (width,
///             height, components, then pixels)
///  - strings: String (one per value), Enum (one name per value),
///             BitMask (the flag names of the one value, e.g. {"SIDES","BOTTOM"})
///  - nodes:   Node (an SFNode holding NULL has none)
struct FieldValue {
  FieldType type;
  std::vector<float> floats;
  std::vector<std::int32_t> ints;
  std::vector<std::string> strings;
  std::vector<std::shared_ptr<Node>> nodes;

  /// Number of values (1 for any SF field, except an empty SFImage still counts 1).
  std::size_t count() const;
  friend bool operator==(const FieldValue&, const FieldValue&) = default;
};

/// A field as read. A field the schema does not know (an unknown field of a
/// known node) has no type: its verbatim text is kept in `raw` and written back.
///
/// Open Inventor adds two marks after (or in place of) a value, both kept and
/// written back: the ignore flag `~` (the field is not applied by property
/// nodes; traversals take their default instead) and a connection
/// `= ENGINE_OR_NODE . field` (kept verbatim; the value read is the one used).
struct Field {
  std::string name;
  FieldValue value;
  std::string raw;
  bool is_raw = false;
  bool ignored = false;    ///< Inventor's `~`
  bool no_value = false;   ///< only `~` or a connection was given: `value` is the default
  std::string connection;  ///< the text after `=`, verbatim; empty if none
  friend bool operator==(const Field&, const Field&) = default;
};

/// One entry of the extension syntax `fields [ SFFloat a, MFVec3f b ]`.
struct FieldDecl {
  FieldType type;
  std::string name;
  friend bool operator==(const FieldDecl&, const FieldDecl&) = default;
};

using NodePtr = std::shared_ptr<Node>;

struct Node {
  std::string type;                 ///< "Separator", or any name for other nodes
  std::string name;                 ///< DEF name, empty if none
  std::vector<Field> fields;        ///< fields given in the file, in order
  std::vector<NodePtr> children;    ///< for group nodes
  std::vector<FieldDecl> declared;  ///< the `fields [...]` declaration, if any
  bool has_declaration = false;     ///< true if `fields [...]` was given
  std::vector<std::string> is_a;    ///< `isA [...]`, for extension nodes
  /// A node whose type is unknown and that declares no fields cannot be parsed:
  /// its body (the text between its braces) is kept verbatim and written back.
  bool is_raw = false;
  std::string raw_body;
  /// A VRML97 / X3D statement kept verbatim (PROTO, ROUTE, PROFILE, ...):
  /// `type` is its keyword, `raw_body` the text after it (no braces).
  bool statement = false;
  int first_line = 0;  ///< where the node was read (0 if built in code)
  int last_line = 0;

  /// The field of that name (the last one if the file gave it twice), or nullptr.
  Field* find(std::string_view field_name);
  const Field* find(std::string_view field_name) const;
  /// The value of a typed field given in the file, or nullptr.
  const FieldValue* value(std::string_view field_name) const;
  /// The value a traversal applies: as value(), but nullptr for a field with
  /// Inventor's ignore flag (the node then acts as if it was not given).
  const FieldValue* applied_value(std::string_view field_name) const;
  /// Sets (or replaces) a typed field.
  void set(std::string_view field_name, FieldValue v);
};

/// A parsed file: its top-level nodes (VRML 1.0 has one; real files may have
/// several) and the header it had.
struct Scene {
  std::string header = "#VRML V1.0 ascii";
  std::vector<NodePtr> roots;
};

/// True if `header` is an Open Inventor ASCII header ("#Inventor V2.1 ascii", ...).
bool is_inventor_header(std::string_view header);

/// The nodes held by fields of `node` (SFNode / MFNode values, e.g. an
/// Inventor shape's vertexProperty), in field order.
std::vector<NodePtr> field_nodes(const Node& node);

/// Deep structural equality: types, names, fields, children and the sharing
/// pattern (a node shared in one graph must be shared the same way in the other).
bool equal(const Scene& a, const Scene& b);

/// A deep copy of `node` and everything below it that keeps the sharing
/// pattern: a node reached twice is copied once (`done` maps originals to
/// their copies; pass the same map to copy several roots of one graph).
NodePtr copy_subtree(const NodePtr& node, std::unordered_map<const Node*, NodePtr>& done);

/// Convenience builders for typed values.
FieldValue make_float(float v);
FieldValue make_floats(FieldKind kind, bool multi, std::vector<float> v);
FieldValue make_long(std::int32_t v);
FieldValue make_longs(std::vector<std::int32_t> v);
FieldValue make_bool(bool v);
/// A new node of `type` without fields or children.
NodePtr make_node(std::string type);
FieldValue make_enum(std::string v);
FieldValue make_string(std::string v);
FieldValue make_strings(std::vector<std::string> v);
/// An SFNode holding `n` (NULL when `n` is null).
FieldValue make_node_value(NodePtr n);
/// An MFNode holding `nodes`.
FieldValue make_nodes_value(std::vector<NodePtr> nodes);

}  // namespace lodforge::scene
