#pragma once
// Test helper: two simplification results are the same, field by field.
#include <gtest/gtest.h>

#include "lodforge/simplify/simplify_result.h"

namespace lodforge::test {

inline void expect_same_result(const SimplifyResult& r, const SimplifyResult& expected) {
  EXPECT_EQ(r.mesh.triangles, expected.mesh.triangles);
  EXPECT_EQ(r.mesh.positions, expected.mesh.positions);
  EXPECT_EQ(r.mesh.normals, expected.mesh.normals);
  EXPECT_EQ(r.mesh.texcoords, expected.mesh.texcoords);
  EXPECT_EQ(r.vertex_map, expected.vertex_map);
  EXPECT_EQ(r.face_map, expected.face_map);
  EXPECT_EQ(r.error, expected.error);
}

}  // namespace lodforge::test
