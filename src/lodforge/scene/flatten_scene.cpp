#include "lodforge/scene/flatten_scene.h"

namespace lodforge::scene {

TriangleMesh flatten_scene(const Scene& scene, const FlattenOptions& options, Log* log) {
  TriangleMesh all;
  traverse(scene,
           [&](const ShapeVisit& v) {
             TriangleMesh m = shape_mesh(v, options.shape, log);
             auto base = static_cast<std::uint32_t>(all.positions.size());
             all.positions.insert(all.positions.end(), m.positions.begin(), m.positions.end());
             for (const auto& t : m.triangles)
               all.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
             for (const auto& l : m.lines) all.lines.push_back({l[0] + base, l[1] + base});
           },
           {.lod_level = options.lod_level, .viewpoint = options.viewpoint});
  return all;
}

}  // namespace lodforge::scene
