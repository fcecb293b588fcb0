#include "lodforge/studio/scene_tree.h"

#include <fmt/core.h>

#include <unordered_set>

namespace lodforge::studio {
namespace {

using nlohmann::json;

// A field as the tree shows it: its values when few, else how many.
std::string summary(const scene::Field& field, std::size_t max_values) {
  const scene::FieldValue& v = field.value;
  if (!field.connection.empty()) return "= " + field.connection;
  const std::size_t scalars = v.floats.size() + v.ints.size() + v.strings.size() + v.nodes.size();
  if (scalars > max_values) return fmt::format("{} values", v.count());
  std::string s;
  const auto add = [&s](const std::string& part) { s += (s.empty() ? "" : " ") + part; };
  for (float f : v.floats) add(fmt::format("{}", f));
  for (std::int32_t i : v.ints) add(std::to_string(i));
  for (const auto& t : v.strings) add(t);
  for (const auto& node : v.nodes) add(node ? node->type : "NULL");
  return s.empty() && !field.raw.empty() ? field.raw : s;
}

json node_json(const scene::Node& node, std::unordered_set<const scene::Node*>& seen,
               const SceneTreeOptions& options) {
  json j = {{"type", node.type}, {"line", node.first_line}};
  if (!node.name.empty()) j["name"] = node.name;
  if (!seen.insert(&node).second) {
    j["use"] = true;
    return j;
  }
  json fields = json::object();
  for (const auto& f : node.fields) fields[f.name] = summary(f, options.max_values);
  j["fields"] = std::move(fields);
  json children = json::array();
  for (const auto& c : node.children) children.push_back(node_json(*c, seen, options));
  for (const auto& c : scene::field_nodes(node))
    if (c) children.push_back(node_json(*c, seen, options));
  j["children"] = std::move(children);
  return j;
}

}  // namespace

json scene_tree(const scene::Scene& scene, const SceneTreeOptions& options) {
  std::unordered_set<const scene::Node*> seen;
  json roots = json::array();
  for (const auto& r : scene.roots) roots.push_back(node_json(*r, seen, options));
  return roots;
}

}  // namespace lodforge::studio
