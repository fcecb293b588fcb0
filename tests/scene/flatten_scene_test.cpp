// A scene flattened to one world-space mesh, at one LOD level or as seen from
// a viewpoint.
#include "lodforge/scene/flatten_scene.h"

#include <gtest/gtest.h>

#include "lodforge/io/vrml1/read_vrml1.h"

namespace lodforge::scene {
namespace {

// Two LOD nodes 100 apart, each switching at 10 from a Cube (12 triangles) to
// a single triangle.
constexpr const char* kTwoLods = R"(#VRML V1.0 ascii
Separator {
  DEF Near LOD { range [10]
    Cube {}
    Separator { Coordinate3 { point [0 0 0, 1 0 0, 0 1 0] } IndexedFaceSet { coordIndex [0, 1, 2, -1] } }
  }
  Translation { translation 100 0 0 }
  USE Near
})";

TEST(FlattenScene, EachLodChoosesByItsOwnDistanceFromTheViewpoint) {
  const vrml1::ReadResult r = vrml1::read_vrml1(kTwoLods);
  // Near the first: its cube and the far one's triangle.
  EXPECT_EQ(flatten_scene(r.scene, {.viewpoint = Vec3{0, 0, 5}}).triangle_count(), 12u + 1u);
  // Near the second: the other way round.
  EXPECT_EQ(flatten_scene(r.scene, {.viewpoint = Vec3{100, 0, 5}}).triangle_count(), 1u + 12u);
  // Midway, both are 50 away: both triangles. Without a viewpoint: lod_level.
  EXPECT_EQ(flatten_scene(r.scene, {.viewpoint = Vec3{50, 0, 0}}).triangle_count(), 2u);
  EXPECT_EQ(flatten_scene(r.scene, {}).triangle_count(), 24u);
  EXPECT_EQ(flatten_scene(r.scene, {.lod_level = 1}).triangle_count(), 2u);
}

}  // namespace
}  // namespace lodforge::scene
