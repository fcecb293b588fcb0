// The VRML97 / X3D LOD pipeline on scenes written as text and on the corpus.
#include "lodforge/lod/generate_lod_vrml97.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/vrml97/write_vrml97.h"

namespace lodforge {
namespace {

using scene::NodePtr;

// A bumpy grid of n x n quads as an IndexedFaceSet with per-vertex texture
// coordinates and per-face colours, DEF S, used twice (once scaled by 2).
std::string grid_scene(const std::string& header, int n) {
  std::string points, tex, index, colors, color_index;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) {
      const double z = 0.05 * std::sin(x * 0.7) * std::cos(y * 0.5);
      points += fmt::format("{} {} {}, ", x / double(n), y / double(n), z);
      tex += fmt::format("{} {}, ", x / double(n), y / double(n));
    }
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x;
      index += fmt::format("{} {} {} {} -1 ", a, a + 1, a + n + 2, a + n + 1);
      color_index += fmt::format("{} ", (x + y) % 2);
    }
  return header + "\nViewpoint { fieldOfView 0.5 }\n" +
         "DEF S Shape { appearance DEF A Appearance { material Material {} }\n"
         "  geometry IndexedFaceSet { solid FALSE colorPerVertex FALSE\n"
         "    coord Coordinate { point [" +
         points +
         "] }\n"
         "    texCoord DEF T TextureCoordinate { point [" +
         tex +
         "] }\n"
         "    color DEF C Color { color [1 0 0, 0 1 0] } colorIndex [" +
         color_index +
         "]\n"
         "    coordIndex [" +
         index +
         "] } }\n"
         "Transform { scale 2 2 2 children [ USE S ] }\n";
}

TEST(GenerateLodVrml97, ShapesBecomeLodsWithLevelsSharingOneCoordinate) {
  auto read = vrml97::read_vrml97(grid_scene("#VRML V2.0 utf8", 30));
  LodResult r = generate_lod_vrml97(std::move(read.scene));
  ASSERT_EQ(r.shapes.size(), 1u);  // the shape USEd twice is one job
  const ShapeStatistics& s = r.shapes[0];
  EXPECT_EQ(s.occurrences, 2u);
  EXPECT_DOUBLE_EQ(s.scale, 2.0);
  EXPECT_FLOAT_EQ(float(r.camera_angle), 0.5f);  // the Viewpoint's fieldOfView
  EXPECT_EQ(s.levels.front().triangles, 30u * 30u * 2u);
  ASSERT_GE(s.levels.size(), 3u);  // level 0, simplified ones, the empty one
  for (std::size_t i = 1; i + 1 < s.levels.size(); ++i)
    EXPECT_LT(s.levels[i].triangles, s.levels[i - 1].triangles);
  EXPECT_EQ(s.ranges.size(), s.levels.size() - 1);
  for (std::size_t i = 1; i < s.ranges.size(); ++i) EXPECT_GT(s.ranges[i], s.ranges[i - 1]);

  // Both places of the shape hold the same LOD; level 0 is the input shape.
  const NodePtr& lod = r.scene.roots[1];
  ASSERT_EQ(lod->type, "LOD");
  const auto& transform_children = r.scene.roots[2]->value("children")->nodes;
  EXPECT_EQ(transform_children.at(0), lod);
  const auto& levels = lod->value("level")->nodes;
  ASSERT_EQ(levels.size(), s.levels.size());
  EXPECT_EQ(levels[0]->name, "S");
  EXPECT_EQ(levels.back()->type, "Group");
  const NodePtr input_geometry = levels[0]->value("geometry")->nodes[0];
  NodePtr shared_coord;
  for (std::size_t i = 1; i + 1 < levels.size(); ++i) {
    const auto& shape = *levels[i];
    EXPECT_EQ(shape.value("appearance")->nodes.at(0), levels[0]->value("appearance")->nodes[0]);
    const auto& ifs = *shape.value("geometry")->nodes.at(0);
    EXPECT_EQ(ifs.type, "IndexedFaceSet");
    const NodePtr coord = ifs.value("coord")->nodes.at(0);
    if (!shared_coord) shared_coord = coord;
    EXPECT_EQ(coord, shared_coord);  // one Coordinate for all simplified levels
    // Attributes are the input's own nodes, indexed per corner / per face.
    EXPECT_EQ(ifs.value("texCoord")->nodes.at(0), input_geometry->value("texCoord")->nodes[0]);
    EXPECT_EQ(ifs.value("color")->nodes.at(0), input_geometry->value("color")->nodes[0]);
    const auto& ci = ifs.value("coordIndex")->ints;
    const std::size_t faces = std::size_t(std::count(ci.begin(), ci.end(), -1));
    EXPECT_EQ(faces, s.levels[i].triangles);
    EXPECT_EQ(ifs.value("colorIndex")->ints.size(), faces);  // per face
    EXPECT_EQ(ifs.value("texCoordIndex")->ints.size(), ci.size());
    for (std::int32_t c : ifs.value("colorIndex")->ints) EXPECT_TRUE(c == 0 || c == 1);
  }
  // Written and read back, the scene is the same (sharing included; the
  // shared nodes made without a name are named "lf_N" when written).
  const std::string text = vrml97::write_vrml97(r.scene);
  const auto back = vrml97::read_vrml97(text);
  EXPECT_EQ(vrml97::write_vrml97(back.scene), text);
  EXPECT_EQ(back.scene.roots.at(1)->value("level")->nodes.at(1)->value("appearance")->nodes.at(0),
            back.scene.roots.at(1)->value("level")->nodes.at(0)->value("appearance")->nodes.at(0));
}

TEST(GenerateLodVrml97, X3dLodsHoldTheirLevelsInChildren) {
  auto read = vrml97::read_vrml97(grid_scene("#X3D V3.2 utf8\nPROFILE Immersive", 8));
  LodResult r = generate_lod_vrml97(std::move(read.scene),
                                    {.range = {.camera_angle = 1.0f}, .camera_angle_given = true});
  EXPECT_FLOAT_EQ(float(r.camera_angle), 1.0f);  // --camera-angle wins over the Viewpoint
  const NodePtr& lod = r.scene.roots[2];
  ASSERT_EQ(lod->type, "LOD");
  EXPECT_EQ(lod->value("level"), nullptr);
  ASSERT_NE(lod->value("children"), nullptr);
  EXPECT_EQ(lod->value("children")->nodes.at(0)->name, "S");
}

TEST(GenerateLodVrml97, AnIndexOutOfRangeLeavesTheShapeAsItIsWithAWarning) {
  auto read = vrml97::read_vrml97(R"(#VRML V2.0 utf8
Shape { geometry IndexedFaceSet { coord Coordinate { point [0 0 0, 1 0 0, 0 1 0] }
                                  coordIndex [0 1 7 -1] } }
)");
  LodResult r = generate_lod_vrml97(std::move(read.scene));
  EXPECT_TRUE(r.shapes.empty());
  EXPECT_EQ(r.scene.roots[0]->type, "Shape");
  ASSERT_FALSE(r.log.entries().empty());
  EXPECT_NE(
      r.log.entries()[0].text.find("line 2: IndexedFaceSet coordIndex[2] = 7 is out of range (the "
                                   "current Coordinate has 3 points); shape "
                                   "left without LOD"),
      std::string::npos)
      << r.log.entries()[0].text;
}

TEST(GenerateLodVrml97, TriangleAndQuadSetsBecomeIndexedFaceSetLevels) {
  auto read = vrml97::read_vrml97_file(std::string(LODFORGE_SHARED_DATA) +
                                       "/x3d/castle-engine__demo-models/x3d/"
                                       "triangle_quad_sets.x3dv");
  LodResult r = generate_lod_vrml97(std::move(read.scene));
  std::set<std::string> types;
  for (const auto& s : r.shapes) types.insert(s.type);
  EXPECT_TRUE(types.count("IndexedTriangleSet"));
  EXPECT_TRUE(types.count("TriangleSet"));
  EXPECT_TRUE(types.count("IndexedQuadSet"));
}

TEST(GenerateLodVrml97, TheTeapotGetsAChainOfLevels) {
  auto read = vrml97::read_vrml97_file(std::string(LODFORGE_SHARED_DATA) +
                                       "/vrml2/castle-engine__demo-models/vrml_2/teapot.wrl");
  LodResult r = generate_lod_vrml97(std::move(read.scene));
  ASSERT_EQ(r.shapes.size(), 1u);
  EXPECT_EQ(r.shapes[0].levels.front().triangles, 3014u);
  EXPECT_GE(r.shapes[0].levels.size(), 5u);
  EXPECT_LT(r.shapes[0].levels[r.shapes[0].levels.size() - 2].triangles, 100u);
  EXPECT_GT(r.shapes[0].scale, 18.0);  // the Transform's scale 18.29
}

}  // namespace
}  // namespace lodforge

namespace lodforge {
namespace {

// The grid scene with its texCoord node replaced by `tex`.
std::string grid_scene_with_tex(const std::string& header, const std::string& tex) {
  std::string s = grid_scene(header, 12);
  const std::size_t b = s.find("texCoord DEF T");
  const std::size_t e = s.find("] }", b) + 3;
  return s.replace(b, e - b, "texCoord " + tex);
}

// Every simplified level's IndexedFaceSet (an X3D scene's LOD: children).
std::vector<NodePtr> level_face_sets(const LodResult& r) {
  std::vector<NodePtr> out;
  const NodePtr& lod = r.scene.roots.at(2);
  const auto& levels = lod->value("children")->nodes;
  for (std::size_t i = 1; i + 1 < levels.size(); ++i)
    out.push_back(levels[i]->value("geometry")->nodes.at(0));
  return out;
}

TEST(GenerateLodVrml97, ComputedTextureCoordinatesAreTheLevelsToo) {
  // A TextureCoordinateGenerator computes coordinates for any geometry: every
  // level uses the input's node, with no index and no warning (the levels
  // were drawn with the default mapping instead, and a warning said an index
  // was out of range).
  auto read = vrml97::read_vrml97(grid_scene_with_tex(
      "#X3D V3.2 utf8\nPROFILE Immersive", "DEF G TextureCoordinateGenerator { mode \"SPHERE\" }"));
  LodResult r = generate_lod_vrml97(std::move(read.scene));
  EXPECT_TRUE(r.log.entries().empty()) << r.log.entries().at(0).text;
  const auto sets = level_face_sets(r);
  ASSERT_GE(sets.size(), 2u);
  for (const NodePtr& ifs : sets) {
    const NodePtr tex = ifs->value("texCoord")->nodes.at(0);
    EXPECT_EQ(tex->type, "TextureCoordinateGenerator");
    EXPECT_EQ(tex->name, "G");
    EXPECT_EQ(ifs->value("texCoordIndex"), nullptr);
  }
}

TEST(GenerateLodVrml97, MultiTextureCoordinatesAreIndexedLikeOneList) {
  // Two coordinate lists and a generator: one texCoordIndex indexes the lists
  // alike, so the levels index the MultiTextureCoordinate exactly as they
  // index the grid's own TextureCoordinate when it stands alone (the first
  // list is that one; the levels were left without coordinates, with a
  // warning).
  const std::string header = "#X3D V3.2 utf8\nPROFILE Immersive";
  std::string own, other;
  for (int y = 0; y <= 12; ++y)
    for (int x = 0; x <= 12; ++x) {
      own += fmt::format("{} {}, ", x / 12.0, y / 12.0);
      other += fmt::format("{} 0.5, ", (13 * y + x) / 168.0);
    }
  auto read = vrml97::read_vrml97(grid_scene_with_tex(
      header, "DEF M MultiTextureCoordinate { texCoord [ TextureCoordinate { point [" + own +
                  "] } TextureCoordinateGenerator {} TextureCoordinate { point [" + other +
                  "] } ] }"));
  LodResult r = generate_lod_vrml97(std::move(read.scene));
  EXPECT_TRUE(r.log.entries().empty()) << r.log.entries().at(0).text;
  LodResult alone = generate_lod_vrml97(vrml97::read_vrml97(grid_scene(header, 12)).scene);
  const auto sets = level_face_sets(r);
  const auto alone_sets = level_face_sets(alone);
  ASSERT_GE(sets.size(), 2u);
  ASSERT_EQ(sets.size(), alone_sets.size());
  for (std::size_t i = 0; i < sets.size(); ++i) {
    EXPECT_EQ(sets[i]->value("texCoord")->nodes.at(0)->name, "M");
    ASSERT_NE(sets[i]->value("texCoordIndex"), nullptr);
    EXPECT_EQ(sets[i]->value("texCoordIndex")->ints, alone_sets[i]->value("texCoordIndex")->ints);
    EXPECT_EQ(sets[i]->value("coordIndex")->ints, alone_sets[i]->value("coordIndex")->ints);
  }
}

// A grid whose left and right halves are two texture islands (texCoordIndex
// into two lists of coordinates, the seam's vertices in both): every level's
// triangle takes its three texture coordinates from one island (a level
// vertex took them from either side of the seam, smearing the texture).
TEST(GenerateLodVrml97, LevelsKeepTextureSeams) {
  const int n = 30, count = (n + 1) * (n + 1);
  std::string points, tex, index, tex_index;
  for (int island = 0; island < 2; ++island)
    for (int y = 0; y <= n; ++y)
      for (int x = 0; x <= n; ++x) {
        if (island == 0)
          points += fmt::format("{} {} {}, ", x / double(n), y / double(n),
                                0.05 * std::sin(x * 0.7) * std::cos(y * 0.5));
        tex += fmt::format("{} {}, ", x / double(n) + 5 * island, y / double(n));
      }
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x, t = a + (2 * x < n ? 0 : count);
      index += fmt::format("{} {} {} {} -1 ", a, a + 1, a + n + 2, a + n + 1);
      tex_index += fmt::format("{} {} {} {} -1 ", t, t + 1, t + n + 2, t + n + 1);
    }
  auto read = vrml97::read_vrml97(
      "#X3D V3.2 utf8\nPROFILE Immersive\nViewpoint { fieldOfView 0.5 }\n"
      "Shape { appearance Appearance { texture ImageTexture { url \"t.png\" } }\n"
      "  geometry IndexedFaceSet { coord Coordinate { point [" +
      points +
      "] }\n"
      "    texCoord TextureCoordinate { point [" +
      tex + "] } texCoordIndex [" + tex_index + "] coordIndex [" + index + "] } }\n");
  LodResult r = generate_lod_vrml97(std::move(read.scene));
  const auto& levels = r.scene.roots.at(2)->value("children")->nodes;
  ASSERT_GE(levels.size(), 4u);
  std::size_t triangles = 0;
  for (std::size_t i = 1; i + 1 < levels.size(); ++i) {
    const auto& t = levels[i]->value("geometry")->nodes.at(0)->value("texCoordIndex")->ints;
    for (std::size_t k = 0; k + 3 < t.size(); k += 4, ++triangles) {
      const bool right = t[k] >= count;
      EXPECT_EQ(t[k + 1] >= count, right) << "level " << i << " triangle " << k / 4;
      EXPECT_EQ(t[k + 2] >= count, right) << "level " << i << " triangle " << k / 4;
    }
  }
  EXPECT_GT(triangles, 0u);
}

TEST(GenerateLodVrml97, ExtractPutsOneLevelInPlaceOfEachShape) {
  // --extract K: level K's Shape where the shape was (both places of the
  // shared one), no LOD; 0 leaves the shape; beyond the last simplified
  // level, the empty one.
  const std::string text = grid_scene("#VRML V2.0 utf8", 30);
  const LodResult full = generate_lod_vrml97(vrml97::read_vrml97(text).scene);
  const auto& levels = full.scene.roots.at(1)->value("level")->nodes;
  ASSERT_GE(levels.size(), 4u);
  for (int k : {0, 1, 2, 50}) {
    const LodResult r = generate_lod_vrml97(vrml97::read_vrml97(text).scene, {.extract = k});
    const NodePtr& at = r.scene.roots.at(1);
    EXPECT_EQ(r.scene.roots.at(2)->value("children")->nodes.at(0), at) << k;
    if (k == 0) {
      EXPECT_EQ(at->name, "S");
      EXPECT_EQ(at->type, "Shape");
      continue;
    }
    const std::size_t level = std::min(std::size_t(k), levels.size() - 1);
    EXPECT_EQ(at->type, levels[level]->type) << k;
    if (level + 1 == levels.size()) continue;  // the empty Group
    EXPECT_EQ(at->value("geometry")->nodes.at(0)->value("coordIndex")->ints,
              levels[level]->value("geometry")->nodes.at(0)->value("coordIndex")->ints)
        << k;
    EXPECT_EQ(vrml97::write_vrml97(r.scene).find("LOD"), std::string::npos);
  }
}

TEST(GenerateLodVrml97, ManualModeSetsTheLevelsAndRanges) {
  // --quality polygon=4: two simplified levels, each with at most half the
  // triangles of the one before; --ranges polygon=1,2: the first two ranges
  // given, the third computed (and above them); polygon=1: no LOD; 0: an
  // empty node in the shape's place.
  const std::string text = grid_scene("#VRML V2.0 utf8", 30);
  LodOptions o;
  o.manual["polygon"] = {.quality = 4, .ranges = {1.f, 2.f}};
  const LodResult r = generate_lod_vrml97(vrml97::read_vrml97(text).scene, o);
  ASSERT_EQ(r.shapes.size(), 1u);
  const auto& s = r.shapes[0];
  ASSERT_EQ(s.levels.size(), 4u);  // level 0, two simplified, the empty one
  EXPECT_LE(s.levels[1].triangles, s.levels[0].triangles / 2);
  EXPECT_LE(s.levels[2].triangles, s.levels[1].triangles / 2);
  const auto& range = r.scene.roots.at(1)->value("range")->floats;
  ASSERT_EQ(range.size(), 3u);
  EXPECT_EQ(range[0], 1.f);
  EXPECT_EQ(range[1], 2.f);
  EXPECT_GT(range[2], 2.f);
  EXPECT_EQ(r.scene.roots.at(1)->value("level")->nodes.size(), 4u);
  for (int q : {0, 1}) {
    o.manual["polygon"] = {.quality = q};
    const LodResult m = generate_lod_vrml97(vrml97::read_vrml97(text).scene, o);
    const NodePtr& at = m.scene.roots.at(1);
    EXPECT_EQ(at->type, q == 0 ? "Group" : "Shape") << q;
    if (q == 0) EXPECT_TRUE(at->fields.empty());
    EXPECT_EQ(m.scene.roots.at(2)->value("children")->nodes.at(0), at) << q;
  }
}

TEST(GenerateLodVrml97, ShapesInParallelGiveTheOneThreadScene) {
  // Six distinct shapes (one with a bad index: its warning keeps its place)
  // made on all cores and on one: the same text, messages and statistics.
  std::string text = "#VRML V2.0 utf8\n";
  for (int k = 0; k < 6; ++k) {
    std::string shape = grid_scene("", 10 + 3 * k);
    shape = shape.substr(shape.find("DEF S"));
    shape = shape.substr(0, shape.find("Transform"));
    text +=
        "Transform { translation " + std::to_string(2 * k) + " 0 0 children [ " + shape + " ] }\n";
  }
  text +=
      "Shape { geometry IndexedFaceSet { coord Coordinate { point [0 0 0, 1 0 0, 0 1 0] }\n"
      "  coordIndex [0 1 7 -1] } }\n";
  const LodResult one = generate_lod_vrml97(vrml97::read_vrml97(text).scene, {.threads = 1});
  const LodResult all = generate_lod_vrml97(vrml97::read_vrml97(text).scene, {.threads = 0});
  ASSERT_EQ(all.shapes.size(), 6u);
  EXPECT_EQ(vrml97::write_vrml97(all.scene), vrml97::write_vrml97(one.scene));
  ASSERT_EQ(all.log.entries().size(), one.log.entries().size());
  for (std::size_t i = 0; i < all.log.entries().size(); ++i)
    EXPECT_EQ(all.log.entries()[i].text, one.log.entries()[i].text);
  for (std::size_t i = 0; i < all.shapes.size(); ++i) {
    EXPECT_EQ(all.shapes[i].line, one.shapes[i].line);
    EXPECT_EQ(all.shapes[i].ranges, one.shapes[i].ranges);
  }
  for (std::size_t i = 1; i < all.shapes.size(); ++i)
    EXPECT_GT(all.shapes[i].line, all.shapes[i - 1].line);  // the scene's order
}

TEST(GenerateLodVrml97, SmallerShapesGetFewerLevelsWhenDifferentiatedBySize) {
  // Two grids, the second under a quarter scale: --quality polygon=5
  // --differentiate-by-size gives the large one 3 simplified levels and the
  // small one, two halvings smaller, 5 - 2 = 3 levels (1 simplified).
  std::string text = "#VRML V2.0 utf8\n";
  for (const char* scale : {"1 1 1", "0.25 0.25 0.25"}) {
    std::string shape = grid_scene("", 24);
    shape = shape.substr(shape.find("DEF S"));
    shape = shape.substr(0, shape.find("Transform"));
    text += std::string("Transform { scale ") + scale + " children [ " + shape + " ] }\n";
  }
  LodOptions o{.differentiate_by_size = true};
  o.manual["polygon"] = {.quality = 5};
  const LodResult r = generate_lod_vrml97(vrml97::read_vrml97(text).scene, o);
  ASSERT_EQ(r.shapes.size(), 2u);
  EXPECT_EQ(r.shapes[0].levels.size(), 5u);  // level 0, 3 simplified, the empty one
  EXPECT_EQ(r.shapes[1].levels.size(), 3u);
  o.differentiate_by_size = false;
  const LodResult same = generate_lod_vrml97(vrml97::read_vrml97(text).scene, o);
  EXPECT_EQ(same.shapes[1].levels.size(), 5u);
}

TEST(GenerateLodVrml97, AnElevationGridGetsIndexedFaceSetLevelsWithItsTextureCoordinates) {
  std::string heights;
  for (int z = 0; z < 20; ++z)
    for (int x = 0; x < 20; ++x) heights += fmt::format("{} ", 0.3 * std::sin(x * 0.4 + z * 0.3));
  auto read = vrml97::read_vrml97(
      "#VRML V2.0 utf8\nShape { geometry ElevationGrid { xDimension 20 "
      "zDimension 20 xSpacing 0.5 zSpacing 0.5 height [" +
      heights + "] } }\n");
  LodResult r = generate_lod_vrml97(std::move(read.scene));
  ASSERT_EQ(r.shapes.size(), 1u);
  EXPECT_EQ(r.shapes[0].type, "ElevationGrid");
  EXPECT_EQ(r.shapes[0].levels[0].triangles, 19u * 19u * 2u);
  const auto& levels = r.scene.roots.at(0)->value("level")->nodes;
  ASSERT_GE(levels.size(), 3u);
  EXPECT_EQ(levels[0]->value("geometry")->nodes.at(0)->type, "ElevationGrid");
  const auto& ifs = *levels[1]->value("geometry")->nodes.at(0);
  EXPECT_EQ(ifs.type, "IndexedFaceSet");
  // The grid's default texture coordinates, s along x and t along z.
  const auto& tex = ifs.value("texCoord")->nodes.at(0)->value("point")->floats;
  ASSERT_EQ(tex.size(), 2u * 400u);
  EXPECT_FLOAT_EQ(tex[2 * 19], 1.f);
  EXPECT_FLOAT_EQ(tex[2 * 19 + 1], 0.f);
  // Faces keep the grid's orientation: normals towards +y.
  const auto& p = ifs.value("coord")->nodes.at(0)->value("point")->floats;
  const auto& ci = ifs.value("coordIndex")->ints;
  int up = 0, down = 0;
  for (std::size_t f = 0; f + 3 < ci.size(); f += 4) {
    auto at = [&](int k, int c) {
      return p[3 * std::size_t(ci[f + std::size_t(k)]) + std::size_t(c)];
    };
    const float ux = at(1, 0) - at(0, 0), uz = at(1, 2) - at(0, 2);
    const float vx = at(2, 0) - at(0, 0), vz = at(2, 2) - at(0, 2);
    (uz * vx - ux * vz > 0 ? up : down)++;
  }
  EXPECT_GT(up, 0);
  EXPECT_EQ(down, 0);
}

}  // namespace
}  // namespace lodforge

namespace lodforge {
namespace {

TEST(GenerateLodVrml97, ASkinnedShapeIsLeftAtFullDetailWithAMessage) {
  auto read = vrml97::read_vrml97(R"(#X3D V4.0 utf8
Skin { shapes Shape { geometry IndexedFaceSet { coord Coordinate { point [0 0 0, 1 0 0, 0 1 0] }
                                                coordIndex [0 1 2 -1] } } }
)");
  LodResult r = generate_lod_vrml97(std::move(read.scene));
  EXPECT_TRUE(r.shapes.empty());
  ASSERT_EQ(r.log.entries().size(), 1u);
  EXPECT_NE(r.log.entries()[0].text.find("line 2: a skinned Shape"), std::string::npos);
  EXPECT_EQ(r.scene.roots[0]->value("shapes")->nodes.at(0)->type, "Shape");
}

}  // namespace
}  // namespace lodforge
