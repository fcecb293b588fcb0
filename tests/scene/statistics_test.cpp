// Scene statistics: distinct nodes, traversed triangles, broken shapes.
#include "lodforge/scene/statistics.h"

#include <gtest/gtest.h>

#include "lodforge/io/vrml1/read_vrml1.h"

namespace lodforge::scene {
namespace {

TEST(SceneStatistics, CountsDistinctNodesAndTraversedTriangles) {
  auto r = vrml1::read_vrml1(R"(#VRML V1.0 ascii
    Separator {
      Coordinate3 { point [0 0 0, 1 0 0, 1 1 0, 0 1 0, 0.5 2 0] }
      DEF Face IndexedFaceSet { coordIndex [0, 1, 2, 3, 4, -1, 0, 1, -1, 0, 1, 2] }
      Translation { translation 0 0 1 }
      USE Face
      IndexedLineSet { coordIndex [0, 1, 2, -1, 3, 4] }
      Cube {}
    })");
  SceneStatistics s = scene_statistics(r.scene);
  EXPECT_EQ(s.node_counts["IndexedFaceSet"], 1u);
  EXPECT_EQ(s.node_counts["Separator"], 1u);
  // Per use: a pentagon (3) + a 2-vertex face (0) + a triangle (1) = 4; used twice.
  EXPECT_EQ(s.ifs_triangles, 8u);
  EXPECT_EQ(s.ifs_faces, 6u);
  EXPECT_EQ(s.ils_segments, 3u);
  EXPECT_EQ(s.coordinate_points, 5u);
  EXPECT_EQ(s.total_triangles, 8u + 12u);
  EXPECT_EQ(s.bounds.hi.z, 2.f);  // the cube, 2 wide, moved by 1
  EXPECT_TRUE(s.problems.empty());
}

TEST(SceneStatistics, IndexOutOfRangeIsReportedWithItsLine) {
  auto r = vrml1::read_vrml1(R"(#VRML V1.0 ascii
Separator {
  Coordinate3 { point [0 0 0, 1 0 0, 1 1 0] }
  IndexedFaceSet { coordIndex [0, 1, 5, -1] }
})");
  SceneStatistics s = scene_statistics(r.scene);
  ASSERT_EQ(s.problems.size(), 1u);
  EXPECT_EQ(s.problems[0],
            "line 4: IndexedFaceSet coordIndex[2] = 5 is out of range (the current Coordinate3 "
            "has 3 points)");
  EXPECT_EQ(s.ifs_triangles, 1u);    // what a renderer is asked to draw
  EXPECT_EQ(s.total_triangles, 0u);  // what can actually be built
}

// info tells what lod would refuse: a shape whose extent is not a float.
TEST(SceneStatistics, ShapeBeyondTheFloatRangeIsReported) {
  auto r = vrml1::read_vrml1(R"(#VRML V1.0 ascii
Separator {
  Cube {}
  Cylinder { radius 1e38 }
})");
  SceneStatistics s = scene_statistics(r.scene);
  ASSERT_EQ(s.problems.size(), 1u);
  EXPECT_EQ(s.problems[0].rfind("line 4: Cylinder reaches beyond the float range", 0), 0u)
      << s.problems[0];
}

}  // namespace
}  // namespace lodforge::scene
