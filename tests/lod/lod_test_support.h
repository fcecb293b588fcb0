#pragma once
// Helpers of the LOD tests: scenes built from meshes, and checks of the
// pipeline's output that every test repeats.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <string>

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
