// What a glTF scene draws as one world-space mesh: each node that uses a
// mesh gets its own placed copy; MSFT_lod levels stand in at a chosen level.
#include "lodforge/io/gltf/scene_mesh.h"

#include <gtest/gtest.h>

#include "gltf_builder.h"
#include "lodforge/core/error.h"

namespace lodforge::gltf {
namespace {

// A model whose mesh 0 is one triangle and mesh 1 two; node 0 (mesh 0, with
// MSFT_lod naming node 2 as its level 1) and node 1 (mesh 0 again, moved by
// +10 in x) are in the scene; node 2 holds mesh 1 and is not.
tinygltf::Model model_with_lod() {
  tinygltf::Model m;
  const int one = testing::add_floats(m, {0, 0, 0, 1, 0, 0, 0, 1, 0}, TINYGLTF_TYPE_VEC3);
  const int two = testing::add_floats(m, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, TINYGLTF_TYPE_VEC3);
  const int quad = testing::add_indices(m, {0, 1, 2, 2, 1, 3});
  for (int mesh = 0; mesh < 2; ++mesh) {
    tinygltf::Primitive p;
    p.attributes["POSITION"] = mesh == 0 ? one : two;
    if (mesh == 1) p.indices = quad;
    p.mode = TINYGLTF_MODE_TRIANGLES;
    m.meshes.emplace_back().primitives.push_back(p);
  }
  m.nodes.resize(3);
  m.nodes[0].mesh = 0;
  m.nodes[0].extensions["MSFT_lod"] = tinygltf::Value(tinygltf::Value::Object{
      {"ids", tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(2)})}});
  m.nodes[1].mesh = 0;
  m.nodes[1].translation = {10, 0, 0};
  m.nodes[2].mesh = 1;
  m.scenes.emplace_back().nodes = {0, 1};
  m.defaultScene = 0;
  return m;
}

TEST(SceneMesh, EveryUseOfAMeshIsPlacedByItsNode) {
  const TriangleMesh level0 = scene_mesh(model_with_lod());
  EXPECT_EQ(level0.triangle_count(), 2u);  // mesh 0 twice; node 2 is not in the scene
  ASSERT_EQ(level0.positions.size(), 6u);
  EXPECT_EQ(level0.positions[4], (Vec3{11, 0, 0}));
  EXPECT_EQ(level0.positions[5], (Vec3{10, 1, 0}));
  EXPECT_EQ(level0.triangles[1], (Triangle{3, 4, 5}));
}

TEST(SceneMesh, LodLevelsStandInForTheirNode) {
  const tinygltf::Model m = model_with_lod();
  // Level 1: node 0 draws node 2's mesh (two triangles); node 1 has no LOD.
  EXPECT_EQ(scene_mesh(m, 1).triangle_count(), 3u);
  // A level beyond the last: the coarsest there is.
  EXPECT_EQ(scene_mesh(m, 5).triangle_count(), 3u);
  tinygltf::Model bad = m;
  bad.nodes[0].extensions["MSFT_lod"] = tinygltf::Value(tinygltf::Value::Object{
      {"ids", tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(7)})}});
  EXPECT_THROW(scene_mesh(bad, 1), DataError);
  EXPECT_EQ(scene_mesh(bad, 0).triangle_count(), 2u);  // level 0 does not look at the ids
}

}  // namespace
}  // namespace lodforge::gltf
