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
      const FieldValue* idx = field_or_default(v.shape, "coordIndex");
      for (auto [b, e] : split_index_runs(idx->ints)) {
        ++s.ifs_faces;
        if (e - b >= 3) s.ifs_triangles += e - b - 2;
      }
    } else if (t == "IndexedLineSet") {
      const FieldValue* idx = field_or_default(v.shape, "coordIndex");
      for (auto [b, e] : split_index_runs(idx->ints)) s.ils_segments += e - b - 1;
    }
    try {
      TriangleMesh m = shape_mesh(v);
      s.total_triangles += m.triangle_count();
      s.total_vertices += m.vertex_count();
      Box3 box;
      for (const auto& p : m.positions) box.add(p);
      s.bounds.add(box);
      // What lod refuses: a shape whose switching distances cannot be floats.
      if (!box.empty() && !std::isfinite(box.diagonal()))
        s.problems.push_back(fmt::format(
            "line {}: {} reaches beyond the float range (its extent is {}): lod refuses it",
            v.shape.first_line, t, box.diagonal()));
    } catch (const DataError& e) {
      s.problems.emplace_back(e.what());
    }
  });
  return s;
}

}  // namespace lodforge::scene
