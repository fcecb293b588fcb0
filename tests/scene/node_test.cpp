#include "lodforge/scene/node.h"

#include <gtest/gtest.h>

namespace lodforge::scene {
namespace {

// Separator { DEF C Coordinate3 {...} IndexedFaceSet {...} USE C }
Scene shared_scene() {
  Scene s;
  auto root = make_node("Separator");
  auto coords = make_node("Coordinate3");
  coords->name = "C";
  coords->set("point", make_floats(FieldKind::kVec3f, true, {0, 0, 0, 1, 0, 0, 0, 1, 0}));
  auto faces = make_node("IndexedFaceSet");
  faces->set("coordIndex", make_longs({0, 1, 2, -1}));
  root->children = {coords, faces, coords};
  s.roots.push_back(root);
  return s;
}

TEST(SceneNode, CopySubtreeKeepsTheSharingPattern) {
  Scene a = shared_scene();
  std::unordered_map<const Node*, NodePtr> done;
  Scene b;
  b.roots.push_back(copy_subtree(a.roots[0], done));
  const auto& kids = b.roots[0]->children;
  ASSERT_EQ(kids.size(), 3u);
  EXPECT_EQ(kids[0], kids[2]);                  // shared in the copy as in the original
  EXPECT_NE(kids[0], a.roots[0]->children[0]);  // but a new node
  EXPECT_TRUE(equal(a, b));
  // The copy is deep: changing it leaves the original as it was.
  kids[0]->set("point", make_floats(FieldKind::kVec3f, true, {0, 0, 0}));
  EXPECT_FALSE(equal(a, b));
}

TEST(SceneNode, EqualComparesTheSharingPatternNotJustTheValues) {
  Scene a = shared_scene();
  Scene b = shared_scene();
  EXPECT_TRUE(equal(a, b));
  // The same values, but the third child a separate node instead of a USE.
  auto& kids = b.roots[0]->children;
  kids[2] = std::make_shared<Node>(*kids[0]);
  EXPECT_FALSE(equal(a, b));
}

TEST(SceneNode, FindReturnsTheLastFieldOfAName) {
  Node n;
  n.type = "Material";
  n.set("transparency", make_float(0.25f));
  Field again;
  again.name = "transparency";
  again.value = make_float(0.5f);
  n.fields.push_back(again);
  ASSERT_NE(n.value("transparency"), nullptr);
  EXPECT_EQ(n.value("transparency")->floats, std::vector<float>{0.5f});
  EXPECT_EQ(n.value("diffuseColor"), nullptr);
  // Inventor's ignore flag: the field is read, but not applied.
  n.find("transparency")->ignored = true;
  EXPECT_NE(n.value("transparency"), nullptr);
  EXPECT_EQ(n.applied_value("transparency"), nullptr);
}

TEST(SceneNode, TypeNamesRoundTrip) {
  for (FieldKind k : {FieldKind::kBool, FieldKind::kColor, FieldKind::kFloat, FieldKind::kLong,
                      FieldKind::kRotation, FieldKind::kString, FieldKind::kVec2f,
                      FieldKind::kVec3f, FieldKind::kMatrix})
    for (bool multi : {false, true}) {
      FieldType t{k, multi};
      FieldType back;
      ASSERT_TRUE(parse_type_name(type_name(t), back)) << type_name(t);
      EXPECT_EQ(back, t);
    }
  FieldType unused;
  EXPECT_FALSE(parse_type_name("SFNoSuchType", unused));
  EXPECT_EQ(type_name({FieldKind::kVec3f, true}), "MFVec3f");
  EXPECT_EQ(float_components(FieldKind::kRotation), 4);
}

TEST(SceneNode, CountOfValues) {
  EXPECT_EQ(make_floats(FieldKind::kVec3f, true, {1, 2, 3, 4, 5, 6}).count(), 2u);
  EXPECT_EQ(make_longs({1, 2, 3}).count(), 3u);
  EXPECT_EQ(make_float(1).count(), 1u);
}

}  // namespace
}  // namespace lodforge::scene
