#include "lodforge/studio/level_geometry.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "lodforge/core/error.h"
#include "lodforge/io/vrml1/read_vrml1.h"

namespace lodforge::studio {
namespace {

using nlohmann::json;

// Two uses of one LOD under different translations: two instances, each
// with its centre in world space, its ranges and the shapes of each level.
TEST(LevelGeometry, EveryLodInstanceWithItsLevelsAndWorldCentre) {
  const auto r = vrml1::read_vrml1(R"(#VRML V1.0 ascii
Separator {
  Cube { }
  Translation { translation 10 0 0 }
  DEF L LOD {
    range [5, 20]
    center 1 0 0
    Separator {
      Coordinate3 { point [0 0 0, 1 0 0, 0 1 0, 1 1 0] }
      IndexedFaceSet { coordIndex [0, 1, 2, -1, 1, 3, 2, -1] }
    }
    Sphere { }
    Separator { }
  }
  Translation { translation 0 5 0 }
  USE L
})");
  const json g = json::parse(level_geometry(r.scene));
  ASSERT_EQ(g["shapes"].size(), 1u);  // the cube outside every LOD
  EXPECT_EQ(g["shapes"][0]["type"], "Cube");
  EXPECT_EQ(g["shapes"][0]["indices"].size(), 36u);
  ASSERT_EQ(g["lods"].size(), 2u);
  for (const auto& lod : g["lods"]) {
    EXPECT_EQ(lod["name"], "L");
    EXPECT_EQ(lod["ranges"], json({5, 20}));
    ASSERT_EQ(lod["levels"].size(), 3u);
    ASSERT_EQ(lod["levels"][0].size(), 1u);
    EXPECT_EQ(lod["levels"][0][0]["indices"], json({0, 1, 2, 1, 3, 2}));
    EXPECT_EQ(lod["levels"][0][0]["positions"].size(), 12u);
    EXPECT_EQ(lod["levels"][1][0]["type"], "Sphere");
    EXPECT_TRUE(lod["levels"][2].empty());
  }
  EXPECT_EQ(g["lods"][0]["center"], json({11, 0, 0}));
  EXPECT_EQ(g["lods"][1]["center"], json({11, 5, 0}));
  // Column-major object-to-world: the translation is in elements 12..14.
  const auto& m = g["lods"][1]["levels"][0][0]["matrix"];
  EXPECT_EQ(m[12], 10);
  EXPECT_EQ(m[13], 5);
  EXPECT_EQ(m[0], 1);
}

TEST(LevelGeometry, TooManyTrianglesIsADataError) {
  const auto r = vrml1::read_vrml1("#VRML V1.0 ascii\nSeparator { Sphere { } }");
  EXPECT_THROW(level_geometry(r.scene, {.max_triangles = 10}), DataError);
}

}  // namespace
}  // namespace lodforge::studio
