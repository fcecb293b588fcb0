#include "lodforge/apps/load_geometry.h"

#include <algorithm>
#include <cctype>
#include <unordered_set>

#include "lodforge/apps/common_options.h"
#include "lodforge/mesh/coordinate_range.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/scene/flatten_scene.h"

namespace lodforge::apps {

bool is_vrml_path(const std::string& path) {
  std::string p = path;
  std::transform(p.begin(), p.end(), p.begin(), [](unsigned char c) { return std::tolower(c); });
  return p.ends_with(".wrl") || p.ends_with(".wrl.gz") || p.ends_with(".vrml");
}

TriangleMesh load_geometry(const std::string& path, int lod_level, const SceneReadSettings& read) {
  const std::string name = path == "-" ? "<stdin>" : path;
  if (!is_vrml_path(path)) {
    TriangleMesh m = read_mesh(path);
    check_coordinate_range(m, name);
    return m;
  }
  vrml1::ReadResult r = read_scene(path, read);
  Log log;
  TriangleMesh m = scene::flatten_scene(r.scene, {.lod_level = lod_level}, &log);
  if (!read.quiet) {
    std::vector<Diagnostic> warnings;
    for (const auto& d : log.entries())
      if (d.level != LogLevel::kMessage) warnings.push_back(d);
    print_diagnostics(warnings);
  }
  check_coordinate_range(m, name);
  return m;
}

std::size_t lod_level_count(const scene::Scene& scene) {
  std::size_t count = 1;
  std::unordered_set<const scene::Node*> seen;
  std::vector<const scene::Node*> stack;
  for (const auto& r : scene.roots) stack.push_back(r.get());
  while (!stack.empty()) {
    const scene::Node* n = stack.back();
    stack.pop_back();
    if (!seen.insert(n).second) continue;
    if (n->type == "LOD") count = std::max(count, n->children.size());
    for (const auto& c : n->children) stack.push_back(c.get());
  }
  return count;
}

}  // namespace lodforge::apps
