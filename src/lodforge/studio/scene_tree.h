#pragma once
/// The node hierarchy of a scene as JSON for the studio's tree view.
#include <nlohmann/json.hpp>

#include "lodforge/scene/node.h"

namespace lodforge::studio {

struct SceneTreeOptions {
  /// A field's values are listed when they are at most this many numbers
  /// (or strings); a longer field is shown by its count of values, a
  /// vector counting once ("3012 values").
  std::size_t max_values = 6;
};

/// `[{"type", "name" (DEF, if any), "line", "fields": {name: summary},
/// "children": [...]}, ...]` for the scene's roots. A node met again (USE)
/// is `{"type", "name", "line", "use": true}` without its fields and
/// children, so a scene that shares a group many times stays small.
nlohmann::json scene_tree(const scene::Scene& scene, const SceneTreeOptions& options = {});

}  // namespace lodforge::studio
