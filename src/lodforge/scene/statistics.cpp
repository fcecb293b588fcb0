#include "lodforge/scene/statistics.h"

#include <fmt/core.h>

#include <cmath>
#include <unordered_set>

#include "lodforge/core/error.h"
#include "lodforge/scene/schema.h"
#include "lodforge/scene/shape_mesh.h"
#include "lodforge/scene/traverse.h"

namespace lodforge::scene {
namespace {

void count_distinct(const NodePtr& n, std::unordered_set<const Node*>& seen, SceneStatistics& s) {
  if (!seen.insert(n.get()).second) return;
  ++s.node_counts[n->type];
  if (n->type == "Coordinate3")
    if (const FieldValue* p = field_or_default(*n, "point")) s.coordinate_points += p->count();
  for (const auto& c : field_nodes(*n)) count_distinct(c, seen, s);  // vertexProperty
  for (const auto& c : n->children) count_distinct(c, seen, s);
}

}  // namespace

SceneStatistics scene_statistics(const Scene& scene) {
  SceneStatistics s;
  std::unordered_set<const Node*> seen;
  for (const auto& r : scene.roots) count_distinct(r, seen, s);
  traverse(scene, [&](const ShapeVisit& v) {
    ++s.shapes_traversed;
    const std::string& t = v.shape.type;
    if (t == "IndexedFaceSet") {
      for_each_index_run(field_or_default(v.shape, "coordIndex")->ints,
                         [&](std::size_t b, std::size_t e) {
                           ++s.ifs_faces;
                           if (e - b >= 3) s.ifs_triangles += e - b - 2;
                         });
    } else if (t == "IndexedLineSet") {
      for_each_index_run(field_or_default(v.shape, "coordIndex")->ints,
                         [&](std::size_t b, std::size_t e) { s.ils_segments += e - b - 1; });
    }
    try {
      const ShapeCounts c = shape_counts(v);
      s.total_triangles += c.triangles;
      s.total_vertices += c.vertices;
      s.bounds.add(c.bounds);
      // What lod refuses: a shape whose switching distances cannot be floats.
      if (!c.bounds.empty() && !std::isfinite(c.bounds.diagonal()))
        s.problems.push_back(fmt::format(
            "line {}: {} reaches beyond the float range (its extent is {}): lod refuses it",
            v.shape.first_line, t, c.bounds.diagonal()));
    } catch (const DataError& e) {
      s.problems.emplace_back(e.what());
    }
  });
  return s;
}

}  // namespace lodforge::scene
