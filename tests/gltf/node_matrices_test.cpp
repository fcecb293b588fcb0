// Where glTF nodes are drawn: local matrices (matrix, or T * R * S) and
// world matrices down the node trees of the shown scene.
#include "lodforge/io/gltf/node_matrices.h"

#include <gtest/gtest.h>

#include "core/expect_near.h"

#include <cmath>

namespace lodforge::gltf {
namespace {

using test::expect_near;

TEST(NodeMatrices, MatrixIsColumnMajorAndTrsIsTranslateRotateScale) {
  tinygltf::Node m;
  // Column-major: the translation (5, 6, 7) is the last column.
  m.matrix = {2, 0, 0, 0, 0, 3, 0, 0, 0, 0, 4, 0, 5, 6, 7, 1};
  expect_near(local_matrix(m).transform_point({1, 1, 1}), {7, 9, 11});
  // A matrix wins over TRS given beside it.
  m.translation = {100, 0, 0};
  expect_near(local_matrix(m).transform_point({0, 0, 0}), {5, 6, 7});

  tinygltf::Node trs;
  trs.translation = {1, 0, 0};
  const double h = std::sqrt(0.5);
  trs.rotation = {0, 0, h, h};  // 90 degrees about +z: x -> y
  trs.scale = {2, 2, 2};
  // Scale first, then rotate, then translate: (1,0,0) -> (2,0,0) -> (0,2,0) -> (1,2,0).
  expect_near(local_matrix(trs).transform_point({1, 0, 0}), {1, 2, 0});
  EXPECT_EQ(local_matrix(tinygltf::Node{}), Mat4::identity());
}

TEST(NodeMatrices, WorldMatricesFollowTheTreeOfTheShownScene) {
  tinygltf::Model model;
  model.nodes.resize(4);
  model.nodes[0].translation = {10, 0, 0};
  model.nodes[0].children = {1};
  model.nodes[1].translation = {0, 1, 0};
  model.nodes[2].translation = {0, 0, 5};  // in scene 1 only
  model.nodes[3].scale = {3, 3, 3};        // in no scene
  model.scenes.resize(2);
  model.scenes[0].nodes = {0};
  model.scenes[1].nodes = {2};
  model.defaultScene = 0;
  const auto shown = node_placements(model);
  ASSERT_EQ(shown.size(), 4u);
  EXPECT_TRUE(shown[0].in_scene && shown[1].in_scene);
  EXPECT_FALSE(shown[2].in_scene || shown[3].in_scene);
  expect_near(shown[1].world.transform_point({0, 0, 0}), {10, 1, 0});
  EXPECT_EQ(shown[3].world, Mat4::identity());
  // Another scene by number.
  const auto other = node_placements(model, 1);
  EXPECT_TRUE(other[2].in_scene);
  EXPECT_FALSE(other[0].in_scene);
  expect_near(other[2].world.transform_point({0, 0, 0}), {0, 0, 5});
  // Without scenes, every node without a parent is a root.
  model.scenes.clear();
  model.defaultScene = -1;
  const auto all = node_placements(model);
  EXPECT_TRUE(all[0].in_scene && all[1].in_scene && all[2].in_scene && all[3].in_scene);
  expect_near(all[3].world.transform_point({1, 1, 1}), {3, 3, 3});
}

}  // namespace
}  // namespace lodforge::gltf
