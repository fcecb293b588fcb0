// The VRML 1.0 traversal state: separators, transform order, switches, LOD.
#include "lodforge/scene/traverse.h"

#include <gtest/gtest.h>

#include <map>

#include "lodforge/io/vrml1/read_vrml1.h"

namespace lodforge::scene {
namespace {

struct Seen {
  std::string type;
  Vec3 origin;  // where the shape's local origin lands in world space
  std::string material;
  const Node* camera;
};

std::vector<Seen> visit_all(const std::string& body, const TraverseOptions& options = {}) {
  auto r = vrml1::read_vrml1("#VRML V1.0 ascii\n" + body);
  static std::vector<vrml1::ReadResult> keep;  // the nodes must outlive the visit
  keep.push_back(std::move(r));
  std::vector<Seen> out;
  traverse(
      keep.back().scene,
      [&](const ShapeVisit& v) {
        out.push_back({v.shape.type, v.state.transform.transform_point({0, 0, 0}),
                       v.state.material ? v.state.material->name : "", v.camera});
      },
      options);
  return out;
}

TEST(Traverse, SeparatorRestoresStateGroupDoesNot) {
  auto seen = visit_all(R"(
    Group {
      Separator { Translation { translation 1 0 0 } DEF A Material {} Cube {} }
      Cube {}
      Group { Translation { translation 0 2 0 } DEF B Material {} }
      Cube {}
    })");
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0].origin, (Vec3{1, 0, 0}));
  EXPECT_EQ(seen[0].material, "A");
  EXPECT_EQ(seen[1].origin, (Vec3{0, 0, 0}));
  EXPECT_EQ(seen[1].material, "");
  EXPECT_EQ(seen[2].origin, (Vec3{0, 2, 0}));
  EXPECT_EQ(seen[2].material, "B");
}

TEST(Traverse, TransformSeparatorKeepsPropertiesButNotTheTransform) {
  auto seen = visit_all(R"(
    Separator {
      TransformSeparator { Translation { translation 5 0 0 } DEF M Material {} }
      Sphere {}
    })");
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].origin, (Vec3{0, 0, 0}));
  EXPECT_EQ(seen[0].material, "M");
}

TEST(Traverse, TransformsComposeInFileOrder) {
  // Translation then Scale: the scale applies first to the shape.
  auto seen = visit_all(R"(
    Separator { Translation { translation 1 0 0 } Scale { scaleFactor 2 2 2 }
                Transform { translation 1 0 0 } Cube {} })");
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].origin, (Vec3{3, 0, 0}));
}

TEST(Traverse, TransformNodeOrderAndMatrixTransform) {
  auto r = vrml1::read_vrml1(R"(#VRML V1.0 ascii
    Transform { translation 1 2 3 rotation 0 0 1 1.5707963 scaleFactor 2 1 1 center 1 0 0 })");
  Mat4 m = local_transform(*r.scene.roots[0]);
  // T C R S C^-1 applied to (2,0,0): C^-1 -> (1,0,0), S -> (2,0,0), R -> (0,2,0),
  // C -> (1,2,0), T -> (2,4,3).
  Vec3 p = m.transform_point({2, 0, 0});
  EXPECT_NEAR(p.x, 2, 1e-5);
  EXPECT_NEAR(p.y, 4, 1e-5);
  EXPECT_NEAR(p.z, 3, 1e-5);
  auto mt = vrml1::read_vrml1(
      "#VRML V1.0 ascii\nMatrixTransform { matrix 1 0 0 0 0 1 0 0 0 0 1 0 7 8 9 1 }");
  EXPECT_EQ(local_transform(*mt.scene.roots[0]).transform_point({0, 0, 0}), (Vec3{7, 8, 9}));
}

TEST(Traverse, SwitchFollowsWhichChild) {
  EXPECT_TRUE(visit_all("Switch { Cube {} Sphere {} }").empty());
  auto one = visit_all("Switch { whichChild 1 Cube {} Sphere {} }");
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].type, "Sphere");
  EXPECT_EQ(visit_all("Switch { whichChild -3 Cube {} Sphere {} }").size(), 2u);
  EXPECT_TRUE(visit_all("Switch { whichChild 7 Cube {} }").empty());
}

TEST(Traverse, LodLevelChoosesTheChildClampedToTheLast) {
  const std::string lod = "LOD { range [10, 20] Cube {} Sphere {} Cone {} }";
  EXPECT_EQ(visit_all(lod, {.lod_level = 0}).at(0).type, "Cube");
  EXPECT_EQ(visit_all(lod, {.lod_level = 1}).at(0).type, "Sphere");
  EXPECT_EQ(visit_all(lod, {.lod_level = 9}).at(0).type, "Cone");
}

TEST(Traverse, ViewpointMakesEachLodChooseByItsOwnDistance) {
  // The centre (1 0 0) lands at (3 0 0) in world space: distances are taken
  // from there. Child 0 below 10, child 1 in [10, 20), child 2 from 20 on.
  const std::string lod = R"(Separator { Translation { translation 2 0 0 }
      LOD { range [10, 20] center 1 0 0 Cube {} Sphere {} Cone {} } })";
  const auto at = [&](float x) { return visit_all(lod, {.viewpoint = Vec3{x, 0, 0}}).at(0).type; };
  EXPECT_EQ(at(3), "Cube");
  EXPECT_EQ(at(12.99f), "Cube");
  EXPECT_EQ(at(13), "Sphere");  // exactly range[0] away
  EXPECT_EQ(at(-16.9f), "Sphere");
  EXPECT_EQ(at(23), "Cone");
  EXPECT_EQ(at(1e6f), "Cone");
  // More ranges than children: clamped to the last child. No range: child 0.
  EXPECT_EQ(visit_all("LOD { range [1, 2, 3] Cube {} Sphere {} }", {.viewpoint = Vec3{0, 0, 9}})
                .at(0)
                .type,
            "Sphere");
  EXPECT_EQ(visit_all("LOD { Cube {} Sphere {} }", {.viewpoint = Vec3{0, 0, 9}}).at(0).type,
            "Cube");
}

TEST(Traverse, FirstPerspectiveCameraIsReported) {
  auto seen = visit_all(R"(
    Separator { Cube {} DEF First PerspectiveCamera {} DEF Second PerspectiveCamera {} Sphere {} })");
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].camera, nullptr);
  ASSERT_NE(seen[1].camera, nullptr);
  EXPECT_EQ(seen[1].camera->name, "First");
}

TEST(Traverse, UsedShapeIsVisitedAtEveryPlace) {
  auto seen = visit_all(R"(
    Separator { DEF Box Cube {} Translation { translation 0 0 4 } USE Box })");
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[1].origin, (Vec3{0, 0, 4}));
}

TEST(Traverse, ForEachNodeVisitsEveryDistinctNodeOnce) {
  // A Cube used twice, a LOD of three levels, and a node held in a field.
  auto r = vrml1::read_vrml1(R"(#VRML V1.0 ascii
    Separator { DEF Box Cube {} USE Box LOD { Cube {} Sphere {} Separator { USE Box } } })");
  NodePtr held = make_node("Box");
  FieldValue geometry;
  geometry.type.kind = FieldKind::kNode;
  geometry.nodes = {held, nullptr};
  r.scene.roots[0]->set("geometry", geometry);
  std::map<std::string, int> count;
  for_each_node(r.scene, [&](const Node& n) { ++count[n.type]; });
  EXPECT_EQ(count,
            (std::map<std::string, int>{{"Cube", 2}, {"LOD", 1}, {"Separator", 2}, {"Sphere", 1}}));
  for_each_node(r.scene, [&](const Node& n) { ++count[n.type]; }, {.field_nodes = true});
  EXPECT_EQ(count["Box"], 1);
  EXPECT_EQ(count["Cube"], 4);
  EXPECT_EQ(lod_level_count(r.scene), 3u);
}

}  // namespace
}  // namespace lodforge::scene
