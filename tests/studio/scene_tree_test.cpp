#include "lodforge/studio/scene_tree.h"

#include <gtest/gtest.h>

#include "lodforge/io/vrml1/read_vrml1.h"

namespace lodforge::studio {
namespace {

TEST(SceneTree, NodesWithDefNamesKeyFieldsAndUsesWithoutChildren) {
  const auto r = vrml1::read_vrml1(R"(#VRML V1.0 ascii
Separator {
  DEF Body Separator {
    Coordinate3 { point [0 0 0, 1 0 0, 0 1 0] }
    IndexedFaceSet { coordIndex [0, 1, 2, -1, 0, 2, 1, -1] }
  }
  Translation { translation 2 0 0 }
  USE Body
})");
  const auto tree = scene_tree(r.scene, {.max_values = 4});
  ASSERT_EQ(tree.size(), 1u);
  const auto& top = tree[0];
  EXPECT_EQ(top["type"], "Separator");
  EXPECT_EQ(top["line"], 2);
  ASSERT_EQ(top["children"].size(), 3u);
  const auto& body = top["children"][0];
  EXPECT_EQ(body["name"], "Body");
  EXPECT_EQ(body["children"][0]["fields"]["point"], "3 values");
  EXPECT_EQ(body["children"][1]["fields"]["coordIndex"], "8 values");
  EXPECT_EQ(top["children"][1]["fields"]["translation"], "2 0 0");
  const auto& use = top["children"][2];
  EXPECT_EQ(use["name"], "Body");
  EXPECT_TRUE(use["use"].get<bool>());
  EXPECT_FALSE(use.contains("children"));
}

}  // namespace
}  // namespace lodforge::studio
