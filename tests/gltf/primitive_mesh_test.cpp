// primitive_mesh: strips and fans become triangles facing as the glTF
// specification orders them; lines become segments.
#include "lodforge/io/gltf/primitive_mesh.h"

#include <gtest/gtest.h>

#include "gltf/gltf_builder.h"
#include "lodforge/core/error.h"

namespace lodforge::gltf {
namespace {

using testing::add_floats;
using testing::add_indices;

tinygltf::Model four_points(int mode) {
  tinygltf::Model m;
  tinygltf::Primitive p;
  p.attributes["POSITION"] =
      add_floats(m, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, TINYGLTF_TYPE_VEC3);
  p.mode = mode;
  m.meshes.emplace_back().primitives.push_back(p);
  return m;
}

TEST(PrimitiveMesh, StripAlternatesWindingFanTurnsAroundTheFirstVertex) {
  auto strip = four_points(TINYGLTF_MODE_TRIANGLE_STRIP);
  EXPECT_EQ(primitive_mesh(strip, strip.meshes[0].primitives[0]).triangles,
            (std::vector<Triangle>{{0, 1, 2}, {2, 1, 3}}));
  auto fan = four_points(TINYGLTF_MODE_TRIANGLE_FAN);
  EXPECT_EQ(primitive_mesh(fan, fan.meshes[0].primitives[0]).triangles,
            (std::vector<Triangle>{{1, 2, 0}, {2, 3, 0}}));
  auto loop = four_points(TINYGLTF_MODE_LINE_LOOP);
  EXPECT_EQ(primitive_mesh(loop, loop.meshes[0].primitives[0]).lines,
            (std::vector<Segment>{{0, 1}, {1, 2}, {2, 3}, {3, 0}}));
}

TEST(PrimitiveMesh, IndexPastTheVerticesIsADataError) {
  auto m = four_points(TINYGLTF_MODE_TRIANGLES);
  m.meshes[0].primitives[0].indices = add_indices(m, {0, 1, 7});
  EXPECT_THROW(primitive_mesh(m, m.meshes[0].primitives[0], 0), DataError);
}

}  // namespace
}  // namespace lodforge::gltf
