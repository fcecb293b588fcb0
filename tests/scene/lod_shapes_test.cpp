// The shapes a scene draws, grouped by LOD occurrence and child, in world
// space: what the glTF and VRML97 conversions start from.
#include "lodforge/scene/lod_shapes.h"

#include <gtest/gtest.h>

#include "lodforge/io/vrml1/read_vrml1.h"

namespace lodforge::scene {
namespace {

TEST(LodShapes, ShapesAreGroupedByLodOccurrenceAndChildInWorldSpace) {
  const Scene s = vrml1::read_vrml1(R"(#VRML V1.0 ascii
Separator {
  Cube { }
  Translation { translation 10 0 0 }
  DEF L LOD {
    range [ 5 ]
    Separator { Cube { } Sphere { } }
    Separator { Cube { } }
  }
  Translation { translation 0 10 0 }
  USE L
  AsciiText { string "x" }
}
)")
                      .scene;
  Log log;
  const LodShapes d = collect_lod_shapes(s, log);
  ASSERT_EQ(d.plain.size(), 2u);  // the cube and the text (no geometry)
  EXPECT_EQ(d.plain[1].node->type, "AsciiText");
  EXPECT_TRUE(d.plain[1].surface.mesh.positions.empty());
  ASSERT_EQ(d.lods.size(), 2u);  // each use of the LOD its own
  std::vector<Vec3> origins;
  for (const auto& [key, g] : d.lods) {
    EXPECT_EQ(g.lod->name, "L");
    ASSERT_EQ(g.levels.size(), 2u);
    EXPECT_EQ(g.levels[0].size(), 2u);
    EXPECT_EQ(g.levels[1].size(), 1u);
    origins.push_back(g.transform.transform_point({0, 0, 0}));
    // World space: the cube of child 1 is about the LOD's origin.
    Box3 box;
    for (const Vec3& p : g.levels[1][0].surface.mesh.positions) box.add(p);
    EXPECT_NEAR(length(box.center() - origins.back()), 0, 1e-5);
  }
  EXPECT_NEAR(length(origins[0] - Vec3{10, 0, 0}), 0, 1e-6);
  EXPECT_NEAR(length(origins[1] - Vec3{10, 10, 0}), 0, 1e-6);
}

}  // namespace
}  // namespace lodforge::scene
