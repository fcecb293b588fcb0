// Scene graph nodes and values; structural equality that respects sharing.
#include "lodforge/scene/node.h"

#include <array>
#include <unordered_map>
#include <utility>

namespace lodforge::scene {
namespace {

constexpr std::array<std::string_view, 14> kKindNames = {
    "BitMask", "Bool",     "Color",  "Enum",  "Float", "Image", "Long",
    "Matrix",  "Rotation", "String", "Vec2f", "Vec3f", "Node",  "UInt32"};

// Equality of two graphs must also see that sharing matches: a node shared in
// one graph must map to one node in the other. The map records the pairing.
class GraphComparer {
 public:
  bool nodes(const NodePtr& a, const NodePtr& b) {
    if (!a || !b) return a == b;
    auto it = pairs_.find(a.get());
    if (it != pairs_.end()) return it->second == b.get();
    auto rit = reverse_.find(b.get());
    if (rit != reverse_.end()) return false;
    pairs_[a.get()] = b.get();
    reverse_[b.get()] = a.get();
    if (a->type != b->type || a->name != b->name || !fields(*a, *b) || a->declared != b->declared ||
        a->has_declaration != b->has_declaration || a->is_a != b->is_a || a->is_raw != b->is_raw ||
        a->raw_body != b->raw_body || a->statement != b->statement ||
        a->children.size() != b->children.size())
      return false;
    for (std::size_t i = 0; i < a->children.size(); ++i)
      if (!nodes(a->children[i], b->children[i])) return false;
    return true;
  }

 private:
  // Fields compare by value, and the nodes they hold (SFNode) as graphs.
  bool fields(const Node& a, const Node& b) {
    if (a.fields.size() != b.fields.size()) return false;
    for (std::size_t i = 0; i < a.fields.size(); ++i) {
      const Field& fa = a.fields[i];
      const Field& fb = b.fields[i];
      if (fa.value.nodes.size() != fb.value.nodes.size()) return false;
      Field plain_a = fa, plain_b = fb;
      plain_a.value.nodes.clear();
      plain_b.value.nodes.clear();
      if (plain_a != plain_b) return false;
      for (std::size_t k = 0; k < fa.value.nodes.size(); ++k)
        if (!nodes(fa.value.nodes[k], fb.value.nodes[k])) return false;
    }
    return true;
  }

  std::unordered_map<const Node*, const Node*> pairs_;
  std::unordered_map<const Node*, const Node*> reverse_;
};

}  // namespace

std::string type_name(FieldType type) {
  std::string s = type.multi ? "MF" : "SF";
  s += kKindNames[static_cast<std::size_t>(type.kind)];
  return s;
}

bool parse_type_name(std::string_view name, FieldType& out) {
  if (name.size() < 3 || (name.substr(0, 2) != "SF" && name.substr(0, 2) != "MF")) return false;
  for (std::size_t i = 0; i < kKindNames.size(); ++i) {
    if (name.substr(2) == kKindNames[i]) {
      out = {static_cast<FieldKind>(i), name[0] == 'M'};
      return true;
    }
  }
  return false;
}

int float_components(FieldKind kind) {
  switch (kind) {
    case FieldKind::kColor:
      return 3;
    case FieldKind::kFloat:
      return 1;
    case FieldKind::kMatrix:
      return 16;
    case FieldKind::kRotation:
      return 4;
    case FieldKind::kVec2f:
      return 2;
    case FieldKind::kVec3f:
      return 3;
    default:
      return 0;
  }
}

std::size_t FieldValue::count() const {
  if (!type.multi) return 1;
  if (int c = float_components(type.kind)) return floats.size() / static_cast<std::size_t>(c);
  switch (type.kind) {
    case FieldKind::kBool:
    case FieldKind::kLong:
    case FieldKind::kUInt32:
      return ints.size();
    case FieldKind::kNode:
      return nodes.size();
    case FieldKind::kString:
    case FieldKind::kEnum:
    case FieldKind::kBitMask:
      return strings.size();
    default:
      return 1;
  }
}

// The last one: a field given twice takes its last value, as in Coin.
Field* Node::find(std::string_view field_name) {
  for (auto it = fields.rbegin(); it != fields.rend(); ++it)
    if (it->name == field_name) return &*it;
  return nullptr;
}

const Field* Node::find(std::string_view field_name) const {
  return const_cast<Node*>(this)->find(field_name);
}

const FieldValue* Node::value(std::string_view field_name) const {
  const Field* f = find(field_name);
  return (f && !f->is_raw) ? &f->value : nullptr;
}

const FieldValue* Node::applied_value(std::string_view field_name) const {
  const Field* f = find(field_name);
  return (f && !f->is_raw && !f->ignored) ? &f->value : nullptr;
}

void Node::set(std::string_view field_name, FieldValue v) {
  if (Field* f = find(field_name)) {
    f->value = std::move(v);
    f->is_raw = false;
    f->raw.clear();
    f->no_value = false;
    return;
  }
  Field f;
  f.name = std::string(field_name);
  f.value = std::move(v);
  fields.push_back(std::move(f));
}

bool equal(const Scene& a, const Scene& b) {
  if (a.roots.size() != b.roots.size()) return false;
  GraphComparer cmp;
  for (std::size_t i = 0; i < a.roots.size(); ++i)
    if (!cmp.nodes(a.roots[i], b.roots[i])) return false;
  return true;
}

FieldValue make_float(float v) {
  return make_floats(FieldKind::kFloat, false, {v});
}

FieldValue make_floats(FieldKind kind, bool multi, std::vector<float> v) {
  FieldValue r;
  r.type = {kind, multi};
  r.floats = std::move(v);
  return r;
}

FieldValue make_long(std::int32_t v) {
  FieldValue r;
  r.type = {FieldKind::kLong, false};
  r.ints = {v};
  return r;
}

FieldValue make_longs(std::vector<std::int32_t> v) {
  FieldValue r;
  r.type = {FieldKind::kLong, true};
  r.ints = std::move(v);
  return r;
}

FieldValue make_bool(bool v) {
  FieldValue r;
  r.type = {FieldKind::kBool, false};
  r.ints = {v ? 1 : 0};
  return r;
}

NodePtr copy_subtree(const NodePtr& node, std::unordered_map<const Node*, NodePtr>& done) {
  auto [it, fresh] = done.try_emplace(node.get());
  if (!fresh) return it->second;
  auto copy = std::make_shared<Node>(*node);
  it->second = copy;
  for (auto& child : copy->children) child = copy_subtree(child, done);
  for (auto& f : copy->fields)
    for (auto& n : f.value.nodes)
      if (n) n = copy_subtree(n, done);
  return copy;
}

bool is_inventor_header(std::string_view header) {
  return header.starts_with("#Inventor V");
}

std::vector<NodePtr> field_nodes(const Node& node) {
  std::vector<NodePtr> out;
  for (const auto& f : node.fields)
    for (const auto& n : f.value.nodes)
      if (n) out.push_back(n);
  return out;
}

NodePtr make_node(std::string type) {
  auto n = std::make_shared<Node>();
  n->type = std::move(type);
  return n;
}

FieldValue make_enum(std::string v) {
  FieldValue r;
  r.type = {FieldKind::kEnum, false};
  r.strings = {std::move(v)};
  return r;
}

FieldValue make_string(std::string v) {
  FieldValue r;
  r.type = {FieldKind::kString, false};
  r.strings = {std::move(v)};
  return r;
}

FieldValue make_strings(std::vector<std::string> v) {
  FieldValue r;
  r.type = {FieldKind::kString, true};
  r.strings = std::move(v);
  return r;
}

FieldValue make_node_value(NodePtr n) {
  FieldValue r;
  r.type = {FieldKind::kNode, false};
  if (n) r.nodes.push_back(std::move(n));
  return r;
}

FieldValue make_nodes_value(std::vector<NodePtr> nodes) {
  FieldValue r;
  r.type = {FieldKind::kNode, true};
  r.nodes = std::move(nodes);
  return r;
}

}  // namespace lodforge::scene
