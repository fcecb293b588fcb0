#pragma once
// What "the same scene" means for the readers' fuzz targets: the written text
// of a scene reads back to it, every float bit for bit (a NaN read is a NaN
// written), the sharing pattern kept, and DEF names kept except where the
// writer documents a renaming: a shared node without a name gets "lf_N", and
// a name a later USE could not reach gets "NAME_N".
#include <cstring>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "lodforge/scene/node.h"

namespace lodforge::fuzz {

using scene::Field;
using scene::Node;
using scene::NodePtr;

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

bool same_field(const Field& a, const Field& b) {
  return a.name == b.name && a.is_raw == b.is_raw && a.raw == b.raw &&
         a.value.type == b.value.type && same_bits(a.value.floats, b.value.floats) &&
         a.value.ints == b.value.ints && a.value.strings == b.value.strings;
}

// `written` is `name` or the writer's renaming of it: "NAME_N" ("lf_N" for
// no name) with N a positive number.
bool renamed(const std::string& name, const std::string& written) {
  const std::string base = (name.empty() ? "lf" : name) + "_";
  if (!written.starts_with(base) || written.size() == base.size()) return false;
  for (std::size_t i = base.size(); i < written.size(); ++i)
    if (written[i] < '0' || written[i] > '9') return false;
  return true;
}

/// Compares a scene with the scene its written text reads back as.
class RoundTripComparer {
 public:
  explicit RoundTripComparer(const lodforge::scene::Scene& a) {
    for (const auto& r : a.roots) count(r);
  }
  bool nodes(const NodePtr& a, const NodePtr& b) {
    auto it = pairs_.find(a.get());
    if (it != pairs_.end()) return it->second == b.get();
    if (!paired_.emplace(b.get()).second) return false;
    pairs_[a.get()] = b.get();
    const bool shared = refs_[a.get()] > 1;
    if (a->type != b->type || !(a->name == b->name || (shared && renamed(a->name, b->name))) ||
        a->fields.size() != b->fields.size() || a->declared != b->declared ||
        a->has_declaration != b->has_declaration || a->is_a != b->is_a || a->is_raw != b->is_raw ||
        a->raw_body != b->raw_body || a->children.size() != b->children.size())
      return false;
    if (a->statement != b->statement) return false;
    for (std::size_t i = 0; i < a->fields.size(); ++i) {
      if (!same_field(a->fields[i], b->fields[i])) return false;
      const auto& na = a->fields[i].value.nodes;
      const auto& nb = b->fields[i].value.nodes;
      if (na.size() != nb.size()) return false;
      for (std::size_t k = 0; k < na.size(); ++k)
        if ((na[k] == nullptr) != (nb[k] == nullptr) || (na[k] && !nodes(na[k], nb[k])))
          return false;
    }
    for (std::size_t i = 0; i < a->children.size(); ++i)
      if (!nodes(a->children[i], b->children[i])) return false;
    return true;
  }

 private:
  void count(const NodePtr& n) {
    if (++refs_[n.get()] > 1) return;
    for (const auto& c : n->children) count(c);
    for (const auto& f : n->fields)
      for (const auto& c : f.value.nodes)
        if (c) count(c);
  }
  std::unordered_map<const Node*, std::size_t> refs_;
  std::unordered_map<const Node*, const Node*> pairs_;
  std::unordered_set<const Node*> paired_;
};

}  // namespace lodforge::fuzz
