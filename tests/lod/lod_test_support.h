#pragma once
// Helpers of the LOD tests: scenes built from meshes, and checks of the
// pipeline's output that every test repeats.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <functional>
#include <string>

#include "lodforge/lod/generate_lod.h"
#include "lodforge/metrics/compare_meshes.h"

#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/scene/schema.h"
#include "lodforge/scene/shape_mesh.h"
#include "lodforge/scene/traverse.h"

namespace lodforge::testing {

/// A VRML 1.0 scene holding `mesh` as one IndexedFaceSet under `prefix`
/// (e.g. transforms), with optional per-face materials.
inline std::string scene_of(const TriangleMesh& mesh, const std::string& prefix = "",
                            bool per_face_materials = false) {
  std::string s = "#VRML V1.0 ascii\nSeparator {\n" + prefix + "\n";
  if (per_face_materials)
    s += "Material { diffuseColor [1 0 0, 0 1 0, 0 0 1] }\nMaterialBinding { value PER_FACE }\n";
  s += "Coordinate3 { point [\n";
  for (const auto& p : mesh.positions) s += fmt::format("{} {} {},\n", p.x, p.y, p.z);
  s += "] }\nIndexedFaceSet { coordIndex [\n";
  for (const auto& t : mesh.triangles) s += fmt::format("{}, {}, {}, -1,\n", t[0], t[1], t[2]);
  s += "] }\n}\n";
  return s;
}

/// Errors measured again with another seed and twice the samples stay within
/// the error the ranges used; on screen, at the switch distance, the level's
/// deviation is at most the error range. `level(k)` is the written scene's
/// level k in world space (errors scale with the transform), `ranges` the
/// ranges of its LOD node.
inline void expect_level_errors_bounded(const LodResult& r,
                                        const std::function<TriangleMesh(int)>& level,
                                        const std::vector<float>& ranges, double error_range,
                                        double camera_angle, std::size_t samples) {
  ASSERT_EQ(r.shapes.size(), 1u);
  const ShapeStatistics& s = r.shapes[0];
  ASSERT_GE(ranges.size() + 1, s.levels.size());
  const TriangleMesh level0 = level(0);
  for (std::size_t k = 1; k < s.levels.size(); ++k) {
    const CompareResult c =
        compare_meshes(level0, level(int(k)), {.samples = 2 * samples, .seed = 77});
    EXPECT_LE(c.hausdorff, s.levels[k].error * s.scale) << "level " << k;
    // Screen fraction of the deviation seen from the switch distance (beyond r).
    const double d = ranges[k - 1] - s.radius * s.scale;
    const double screen = c.hausdorff / (2 * d * std::tan(camera_angle / 2));
    EXPECT_LE(screen, error_range * (1 + 1e-6)) << "level " << k;
  }
}

/// Index fields in range for what they index, under each shape's state.
inline void expect_indices_in_range(const scene::Scene& s) {
  scene::traverse(s, [](const scene::ShapeVisit& v) {
    if (v.shape.type != "IndexedFaceSet" && v.shape.type != "IndexedLineSet") return;
    auto count = [](const scene::Node* n, const char* field, std::size_t per) -> std::size_t {
      if (!n) return 0;
      const scene::FieldValue* f = scene::field_or_default(*n, field);
      return f->floats.size() / per;
    };
    auto check = [&](const char* field, std::size_t limit) {
      const scene::FieldValue* idx = v.shape.value(field);
      if (!idx) return;
      for (std::int32_t i : idx->ints)
        EXPECT_TRUE(i == -1 || (i >= 0 && std::size_t(i) < limit))
            << v.shape.type << " line " << v.shape.first_line << " " << field << " " << i << " of "
            << limit;
    };
    check("coordIndex", count(v.state.coordinate3, "point", 3));
    check("normalIndex", count(v.state.normal, "vector", 3));
    check("textureCoordIndex", count(v.state.texture_coordinate2, "point", 2));
    if (v.state.material) {
      std::size_t rows = 0;
      for (const auto& f : v.state.material->fields) rows = std::max(rows, f.value.count());
      check("materialIndex", std::max<std::size_t>(rows, 1));
    }
  });
}

/// Every LOD node: one child more than ranges, ranges increasing; returns
/// the number of LOD nodes.
inline std::size_t expect_lod_structure(const scene::Scene& s) {
  std::size_t lods = 0;
  std::vector<const scene::Node*> stack;
  for (const auto& r : s.roots) stack.push_back(r.get());
  while (!stack.empty()) {
    const scene::Node* n = stack.back();
    stack.pop_back();
    if (n->type == "LOD") {
      ++lods;
      const scene::FieldValue* range = scene::field_or_default(*n, "range");
      EXPECT_EQ(n->children.size(), range->floats.size() + 1);
      for (std::size_t i = 1; i < range->floats.size(); ++i)
        EXPECT_LT(range->floats[i - 1], range->floats[i]);
    }
    for (const auto& c : n->children) stack.push_back(c.get());
  }
  return lods;
}

}  // namespace lodforge::testing
