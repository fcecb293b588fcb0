// Joining small IndexedFaceSets (original §4.1.5).
#include "lodforge/lod/join_nodes.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/lod/generate_lod.h"
#include "lodforge/metrics/compare_meshes.h"
#include "lodforge/scene/flatten_scene.h"
#include "lodforge/scene/statistics.h"

namespace lodforge {
namespace {

using ::testing::ElementsAre;

const char* kTwoParts = R"(#VRML V1.0 ascii
Separator {
  Separator {
    Material { diffuseColor 0.5 0.6 0.4 }
    Coordinate3 { point [0 0 0, 1 0 0, 1 1 0] }
    IndexedFaceSet { coordIndex [0, 1, 2, -1] }
  }
  Separator {
    Separator {
      Material { diffuseColor 0.3 0.3 0.3 transparency 0.5 }
      Coordinate3 { point [1 0 0, 2 0 0, 2 1 0, 1 1 0] }
      IndexedFaceSet { coordIndex [0, 1, 2, 3] }
    }
  }
  Cube {}
}
)";

TEST(JoinNodes, TheOriginalsExampleBecomesOneIndexedFaceSetWithCompleteMaterials) {
  scene::Scene s = vrml1::read_vrml1(kTwoParts).scene;
  TriangleMesh before = scene::flatten_scene(s);
  Log log;
  JoinStatistics js = join_nodes(s, {}, log);
  EXPECT_EQ(js.runs, 1u);
  EXPECT_EQ(js.joined, 1u);
  EXPECT_EQ(js.separators_removed, 1u);
  scene::SceneStatistics st = scene::scene_statistics(s);
  EXPECT_EQ(st.node_counts["IndexedFaceSet"], 1u);
  EXPECT_EQ(st.node_counts["Material"], 1u);
  const scene::Node& joined = *s.roots[0]->children[0];
  const scene::Node& material = *joined.children[0];
  EXPECT_EQ(material.value("diffuseColor")->floats,
            (std::vector<float>{0.5f, 0.6f, 0.4f, 0.3f, 0.3f, 0.3f}));
  // Complete lists: the fields a piece did not give take their defaults.
  EXPECT_EQ(material.value("ambientColor")->count(), 2u);
  EXPECT_THAT(material.value("transparency")->floats, ElementsAre(0.f, 0.5f));
  EXPECT_EQ(joined.children[1]->value("value")->strings[0], "PER_FACE_INDEXED");
  const scene::Node& ifs = *joined.children.back();
  EXPECT_THAT(ifs.value("coordIndex")->ints, ElementsAre(0, 1, 2, -1, 3, 4, 5, 6, -1));
  EXPECT_THAT(ifs.value("materialIndex")->ints, ElementsAre(0, 1));
  EXPECT_EQ(log.entries().back().category, LogCategory::kJoin);
  // The same surface as before, and still valid VRML.
  TriangleMesh after = scene::flatten_scene(s);
  EXPECT_EQ(after.triangle_count(), before.triangle_count());
  EXPECT_EQ(compare_meshes(before, after).hausdorff, 0.0);
  EXPECT_TRUE(scene::equal(s, vrml1::read_vrml1(vrml1::write_vrml1(s)).scene));
}

TEST(JoinNodes, NamedOrSharedPiecesStayApart) {
  std::string text = kTwoParts;
  text.replace(text.find("Material { diffuseColor 0.5"), 8, "DEF Keep Material");
  scene::Scene s = vrml1::read_vrml1(text).scene;
  Log log;
  EXPECT_EQ(join_nodes(s, {}, log).joined, 0u);
  EXPECT_EQ(scene::scene_statistics(s).node_counts["IndexedFaceSet"], 2u);
}

TEST(JoinNodes, BigPiecesAreNotJoined) {
  scene::Scene s = vrml1::read_vrml1(kTwoParts).scene;
  Log log;
  EXPECT_EQ(join_nodes(s, {.max_faces = 0}, log).joined, 0u);
}

TEST(JoinNodes, TheLodPipelineJoinsFirst) {
  scene::Scene s = vrml1::read_vrml1(kTwoParts).scene;
  LodResult plain = generate_lod(s, {.measure_samples = 5000});
  LodResult joined = generate_lod(s, {.join = true, .measure_samples = 5000});
  EXPECT_EQ(plain.shapes.size(), 3u);   // two face sets and the cube
  EXPECT_EQ(joined.shapes.size(), 2u);  // one face set and the cube
  EXPECT_EQ(joined.joined, 1u);
}

}  // namespace
}  // namespace lodforge
