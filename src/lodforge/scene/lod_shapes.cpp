#include "lodforge/scene/lod_shapes.h"

#include <optional>

namespace lodforge::scene {
namespace {

bool is_lod_node(const Node& n) {
  return n.type == "LOD" || n.type == "LevelOfDetail";
}

// Where a shape is drawn: the innermost LOD node on its path (identified by
// the child indices leading to it) and the child of it the shape is under.
struct LodPlace {
  std::vector<std::size_t> key;
  const Node* lod = nullptr;
  Mat4 transform;
  std::size_t child = 0;
};

std::optional<LodPlace> lod_place(const ShapeVisit& v) {
  for (std::size_t i = v.path.size(); i-- > 0;) {
    if (!is_lod_node(*v.path[i])) continue;
    LodPlace p;
    p.lod = v.path[i];
    p.key.assign(v.path_index.begin(), v.path_index.begin() + std::ptrdiff_t(i + 1));
    if (i < v.path_transform.size()) p.transform = v.path_transform[i];
    p.child = i + 1 < v.path.size() ? v.path_index[i + 1] : v.child_index;
    return p;
  }
  return std::nullopt;
}

}  // namespace

LodShapes collect_lod_shapes(const Scene& s, Log& log) {
  LodShapes out;
  const std::size_t levels = lod_level_count(s);
  for (std::size_t k = 0; k < levels; ++k) {
    traverse(s,
             [&](const ShapeVisit& v) {
               if (!out.camera && v.camera) out.camera = v.camera;
               const std::optional<LodPlace> place = lod_place(v);
               // Each shape once: at the traversal that shows its LOD child.
               if (place ? place->child != k : k != 0) return;
               DrawnShape shape{shape_surface(v, {.world_space = true}, &log), &v.shape};
               if (!place) {
                 out.plain.push_back(std::move(shape));
                 return;
               }
               LodGroup& g = out.lods[place->key];
               g.lod = place->lod;
               g.transform = place->transform;
               g.levels.resize(place->lod->children.size());
               g.levels[place->child].push_back(std::move(shape));
             },
             {.lod_level = int(k)});
  }
  return out;
}

}  // namespace lodforge::scene
