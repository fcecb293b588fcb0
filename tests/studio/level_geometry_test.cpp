#include "lodforge/studio/level_geometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <set>

#include "lodforge/core/error.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/lod/generate_lod.h"
#include "lodforge/scene/flatten_scene.h"

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

// Level 1 lifted off level 0's square by 0.25 and 0.5 (under a
// translation, so the distances are taken in world space): its vertices'
// deviations are those heights, and their colours are the scale of `compare
// --colored` at max 0.5 (green at half, red at the maximum); level 0 is blue.
TEST(LevelGeometry, DeviationOfEachLevelFromLevelZero) {
  const auto r = vrml1::read_vrml1(R"(#VRML V1.0 ascii
Separator {
  Translation { translation 3 0 0 }
  LOD {
    range [10]
    Separator {
      Coordinate3 { point [0 0 0, 2 0 0, 0 2 0, 2 2 0] }
      IndexedFaceSet { coordIndex [0, 1, 2, -1, 1, 3, 2, -1] }
    }
    Separator {
      Scale { scaleFactor 1 1 0.5 }
      Coordinate3 { point [0.5 0.5 0.5, 1.5 0.5 0.5, 0.5 1.5 1] }
      IndexedFaceSet { coordIndex [0, 1, 2, -1] }
    }
  }
})");
  const json g = json::parse(level_geometry(r.scene));
  EXPECT_FLOAT_EQ(g["deviation_max"].get<float>(), 0.5f);
  const auto& levels = g["lods"][0]["levels"];
  EXPECT_EQ(levels[0][0]["deviation"], json({0, 0, 0, 0}));
  EXPECT_EQ(levels[0][0]["deviation_colors"], json({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}));
  const auto d = levels[1][0]["deviation"].get<std::vector<float>>();
  ASSERT_EQ(d.size(), 3u);
  EXPECT_FLOAT_EQ(d[0], 0.25f);
  EXPECT_FLOAT_EQ(d[1], 0.25f);
  EXPECT_FLOAT_EQ(d[2], 0.5f);
  const auto c = levels[1][0]["deviation_colors"].get<std::vector<float>>();
  EXPECT_EQ(c, std::vector<float>({0, 1, 0, 0, 1, 0, 1, 0, 0}));
  EXPECT_FALSE(json::parse(level_geometry(r.scene, {.deviation = false}))["lods"][0]["levels"][1][0]
                   .contains("deviation"));
}

TEST(LevelGeometry, TooManyTrianglesIsADataError) {
  const auto r = vrml1::read_vrml1("#VRML V1.0 ascii\nSeparator { Sphere { } }");
  EXPECT_THROW(level_geometry(r.scene, {.max_triangles = 10}), DataError);
}

}  // namespace
}  // namespace lodforge::studio

namespace lodforge::studio {
namespace {

// What the page draws from `eye` (each LOD instance's child by the distance
// from the eye to its centre, VRML 1.0's rule that THREE.LOD follows with
// addLevel at the ranges), counted from the JSON.
std::size_t triangles_seen(const json& g, const Vec3& eye) {
  std::size_t n = 0;
  for (const auto& s : g["shapes"]) n += s["indices"].size() / 3;
  for (const auto& lod : g["lods"]) {
    const auto c = lod["center"].get<std::vector<float>>();
    const float d = length(Vec3{c[0], c[1], c[2]} - eye);
    const auto ranges = lod["ranges"].get<std::vector<float>>();
    std::size_t child = std::upper_bound(ranges.begin(), ranges.end(), d) - ranges.begin();
    child = std::min(child, lod["levels"].size() - 1);
    for (const auto& m : lod["levels"][child]) n += m["indices"].size() / 3;
  }
  return n;
}

// The example scene after `lod`: from every eye position, the levels of the
// JSON switched by their ranges draw as many triangles as the written file
// does in a VRML 1.0 browser (flatten_scene with a viewpoint).
TEST(LevelGeometry, SwitchingByTheJsonDrawsWhatTheWrittenFileDraws) {
  const auto input = vrml1::read_vrml1_file(std::string(LODFORGE_EXAMPLES) + "/scene.wrl");
  const LodResult lod = generate_lod(input.scene);
  const scene::Scene written = vrml1::read_vrml1(vrml1::write_vrml1(lod.scene)).scene;
  const json g = json::parse(level_geometry(written));
  ASSERT_GT(g["lods"].size(), 3u);
  const Box3 box = scene::flatten_scene(written).bounds();
  const Vec3 centre = (box.lo + box.hi) * 0.5f;
  std::set<std::size_t> counts;
  for (float d : {1.f, 50.f, 120.f, 200.f, 400.f, 1000.f, 3000.f, 20000.f})
    for (const Vec3& dir : {Vec3{0, 0, 1}, Vec3{1, 0.5f, 0.2f} / length(Vec3{1, 0.5f, 0.2f})}) {
      const Vec3 eye = centre + dir * d;
      const std::size_t drawn = scene::flatten_scene(written, {.viewpoint = eye}).triangles.size();
      EXPECT_EQ(triangles_seen(g, eye), drawn) << "eye at " << d;
      counts.insert(drawn);
    }
  EXPECT_GT(counts.size(), 4u) << "the eye positions should see several levels";
}

}  // namespace
}  // namespace lodforge::studio
