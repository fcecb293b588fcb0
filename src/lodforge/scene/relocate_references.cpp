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

// Whether `field` of `n` holds file references.
bool is_reference(const Node& n, const Field& field) {
  if (field.is_raw) return false;
  const std::string& f = field.name;
  if (n.type == "Texture2") return f == "filename";
  if (n.type == "WWWInline" || n.type == "WWWAnchor") return f == "name";
  return f == "url" || (f.size() > 3 && f.ends_with("Url"));
}

// `ref` as seen from `to`, or empty when it stays as it is.
std::string moved(const std::string& ref, const fs::path& from, const fs::path& to) {
  const std::size_t first = ref.find_first_not_of(" \t\r\n");
  if (first == std::string::npos || ref.find('\n') != std::string::npos || ref[first] == '#')
    return {};
  const std::string trimmed = ref.substr(first);
  if (has_scheme(trimmed)) return {};
  const std::size_t hash = trimmed.find('#');
  const std::string path = trimmed.substr(0, hash);
  if (fs::path(path).is_absolute()) return {};
  const fs::path target = (from / path).lexically_normal();
  std::string out = target.lexically_relative(to).generic_string();
  if (out.empty()) out = target.generic_string();
  if (hash != std::string::npos) out += trimmed.substr(hash);
  return out == ref ? std::string() : out;
}

}  // namespace

RelocateResult relocate_references(Scene& scene, const fs::path& from_dir, const fs::path& to_dir) {
  RelocateResult result;
  const fs::path from = normal_absolute(from_dir.empty() ? fs::path(".") : from_dir);
  const fs::path to = normal_absolute(to_dir.empty() ? fs::path(".") : to_dir);
  if (from == to) return result;
  std::unordered_set<const Node*> seen;
  std::vector<Node*> stack;
  for (const auto& r : scene.roots) stack.push_back(r.get());
  while (!stack.empty()) {
    Node* n = stack.back();
    stack.pop_back();
    if (!n || !seen.insert(n).second) continue;
    for (const auto& c : n->children) stack.push_back(c.get());
    for (Field& field : n->fields) {
      for (const auto& c : field.value.nodes) stack.push_back(c.get());
      if (!is_reference(*n, field)) continue;
      bool changed = false;
      for (std::string& ref : field.value.strings) {
        std::string m = moved(ref, from, to);
        if (m.empty()) continue;
        ref = std::move(m);
        changed = true;
      }
      result.rewritten += changed;
    }
  }
  return result;
}

}  // namespace lodforge::scene
