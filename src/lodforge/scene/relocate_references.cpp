// Relative file references follow the scene to its new folder.
#include "lodforge/scene/relocate_references.h"

#include <cctype>
#include <string>
#include <unordered_set>
#include <vector>

namespace lodforge::scene {
namespace {

namespace fs = std::filesystem;

// "http://...", "file:...": a URL, not a path (a drive letter "C:" has one
// character before the colon and counts as a path).
bool has_scheme(const std::string& ref) {
  const auto colon = ref.find(':');
  if (colon == std::string::npos || colon < 2) return false;
  for (std::size_t i = 0; i < colon; ++i)
    if (!std::isalnum(static_cast<unsigned char>(ref[i])) && ref[i] != '+' && ref[i] != '-' &&
        ref[i] != '.')
      return false;
  return true;
}

fs::path normal_absolute(const fs::path& p) {
  return fs::absolute(p).lexically_normal();
}

}  // namespace

RelocateResult relocate_references(Scene& scene, const fs::path& from_dir, const fs::path& to_dir) {
  RelocateResult result;
  const fs::path from = normal_absolute(from_dir.empty() ? fs::path(".") : from_dir);
  const fs::path to = normal_absolute(to_dir.empty() ? fs::path(".") : to_dir);
  if (from == to) return result;
  struct Reference {
    const char* type;
    const char* field;
  };
  static constexpr Reference kReferences[] = {{"Texture2", "filename"}, {"WWWInline", "name"}};
  std::unordered_set<const Node*> seen;
  std::vector<Node*> stack;
  for (const auto& r : scene.roots) stack.push_back(r.get());
  while (!stack.empty()) {
    Node* n = stack.back();
    stack.pop_back();
    if (!seen.insert(n).second) continue;
    for (const auto& c : n->children) stack.push_back(c.get());
    for (const Reference& ref : kReferences) {
      if (n->type != ref.type) continue;
      const FieldValue* v = n->value(ref.field);
      if (!v || v->strings.empty()) continue;
      const std::string& name = v->strings[0];
      if (name.empty() || has_scheme(name) || fs::path(name).is_absolute()) continue;
      const fs::path target = (from / name).lexically_normal();
      std::string moved = target.lexically_relative(to).generic_string();
      if (moved.empty()) moved = target.generic_string();
      if (moved == name) continue;
      n->set(ref.field, make_string(moved));
      ++result.rewritten;
    }
  }
  return result;
}

}  // namespace lodforge::scene
