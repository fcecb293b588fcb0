// A VRML97 scene as one world-space surface: transforms (scale about a
// centre, rotation), a LOD's chosen level, Switch, primitives and colours.
#include "lodforge/lod/flatten_vrml97.h"

#include <gtest/gtest.h>

#include "lodforge/io/vrml97/read_vrml97.h"

namespace lodforge {
namespace {

FlatVrml97 flat(const std::string& body, const FlattenVrml97Options& options = {}) {
  Log log;
  return flatten_vrml97(vrml97::read_vrml97("#VRML V2.0 utf8\n" + body).scene, options, log);
}

constexpr const char* kQuad =
    "Shape { appearance Appearance { material Material { diffuseColor 1 0 0 } } "
    "geometry IndexedFaceSet { coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] } "
    "coordIndex [0 1 2 3 -1] } }";

TEST(FlattenVrml97, TransformsScaleAboutTheirCentreAndTranslate) {
  const FlatVrml97 f = flat(std::string("Transform { translation 10 0 0 scale 2 2 2 center 1 1 0 "
                                        "children [") +
                            kQuad + "] }");
  EXPECT_EQ(f.shapes, 1u);
  ASSERT_EQ(f.flat.mesh.triangle_count(), 2u);
  const Box3 b = f.flat.mesh.bounds();
  // x: (0..1 - 1) * 2 + 1 + 10 = 9..11; y: -1..1.
  EXPECT_FLOAT_EQ(b.lo.x, 9);
  EXPECT_FLOAT_EQ(b.hi.x, 11);
  EXPECT_FLOAT_EQ(b.lo.y, -1);
  EXPECT_FLOAT_EQ(b.hi.y, 1);
  ASSERT_EQ(f.flat.mesh.colors.size(), 4u);
  EXPECT_EQ(f.flat.mesh.colors[0], (Vec3{1, 0, 0}));
}

TEST(FlattenVrml97, LodLevelSwitchChoiceAndPrimitives) {
  const std::string lod =
      std::string("LOD { range [10] level [ Shape { geometry Box {} } ") + kQuad + " ] }";
  EXPECT_EQ(flat(lod).flat.mesh.triangle_count(), 12u);  // the Box: level 0
  EXPECT_EQ(flat(lod, {.lod_level = 1}).flat.mesh.triangle_count(), 2u);
  EXPECT_EQ(flat(lod, {.viewpoint = Vec3{0, 0, 5}}).flat.mesh.triangle_count(), 12u);
  EXPECT_EQ(flat(lod, {.viewpoint = Vec3{0, 0, 50}}).flat.mesh.triangle_count(), 2u);
  const std::string sw =
      std::string("Switch { whichChoice 1 choice [ Shape { geometry Sphere {} } ") + kQuad + " ] }";
  EXPECT_EQ(flat(sw).flat.mesh.triangle_count(), 2u);
  EXPECT_EQ(flat("Switch { choice [ Shape { geometry Box {} } ] }").flat.mesh.triangle_count(), 0u);
  const FlatVrml97 cone = flat("Shape { geometry Cone { bottom FALSE } }");
  const FlatVrml97 closed = flat("Shape { geometry Cone {} }");
  EXPECT_GT(cone.flat.mesh.triangle_count(), 0u);
  EXPECT_LT(cone.flat.mesh.triangle_count(), closed.flat.mesh.triangle_count());
  EXPECT_TRUE(closed.flat.mesh.colors.empty());  // no Material, no Color: a plain mesh
}

// Colours per face (colorPerVertex FALSE): each face in its own colour,
// also where faces share a corner.
TEST(FlattenVrml97, ColoursPerFace) {
  const FlatVrml97 f = flat(
      "Shape { geometry IndexedFaceSet { colorPerVertex FALSE "
      "color Color { color [1 0 0, 0 0 1] } colorIndex [1 0] "
      "coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] } coordIndex [0 1 2 -1 0 2 3 -1] } }");
  ASSERT_EQ(f.flat.mesh.triangle_count(), 2u);
  const auto& c = f.flat.mesh.colors;
  ASSERT_EQ(c.size(), f.flat.mesh.vertex_count());
  for (std::uint32_t v : f.flat.mesh.triangles[0]) EXPECT_EQ(c[v], (Vec3{0, 0, 1}));
  for (std::uint32_t v : f.flat.mesh.triangles[1]) EXPECT_EQ(c[v], (Vec3{1, 0, 0}));
}

// An ImageTexture: its first URL, once per node, its texture coordinates,
// and VRML97's default mapping where the geometry has none.
TEST(FlattenVrml97, TexturesAndTheirCoordinates) {
  const std::string face =
      "coord Coordinate { point [0 0 0, 2 0 0, 2 1 0, 0 1 0] } coordIndex [0 1 2 3 -1]";
  const FlatVrml97 f = flat(
      "Shape { appearance Appearance { texture DEF T ImageTexture { url [\"a.png\" \"b.png\"] "
      "repeatS FALSE } } geometry IndexedFaceSet { " +
      face +
      " texCoord TextureCoordinate { point [0 0, 1 0, 1 1, 0 1] } } } "
      "Shape { appearance Appearance { texture USE T } geometry IndexedFaceSet { " +
      face + " } }");
  ASSERT_EQ(f.flat.textures.size(), 1u);
  EXPECT_EQ(f.flat.textures[0].filename, "a.png");
  EXPECT_FALSE(f.flat.textures[0].repeat_s);
  EXPECT_TRUE(f.flat.textures[0].repeat_t);
  const TriangleMesh& m = f.flat.mesh;
  ASSERT_EQ(m.materials.size(), 4u);
  for (std::uint32_t t : m.materials) EXPECT_EQ(t, 0u);
  ASSERT_EQ(m.texcoords.size(), 8u);
  EXPECT_EQ(m.texcoords[2], (Vec2{1, 1}));
  // The default mapping: s along x (the longest side, 2), t along y in the same units.
  EXPECT_EQ(m.texcoords[6], (Vec2{1, 0.5f}));
}

// A TextureTransform: Tc' = -C × S × R × C × T × Tc (ISO/IEC 14772-1 6.49,
// X3D 18.4.8; as Castle Model Viewer draws it).
TEST(FlattenVrml97, TextureTransformMovesTheTextureCoordinates) {
  const FlatVrml97 f = flat(
      "Shape { appearance Appearance { texture ImageTexture { url \"a.png\" } "
      "textureTransform TextureTransform { translation 1 0 scale 2 3 center 0.5 0.5 } } "
      "geometry IndexedFaceSet { coord Coordinate { point [0 0 0, 1 0 0, 0 1 0] } "
      "coordIndex [0 1 2 -1] texCoord TextureCoordinate { point [0 0, 1 0, 0 1] } } }");
  const TriangleMesh& m = f.flat.mesh;
  ASSERT_EQ(m.texcoords.size(), 3u);
  // (0, 0): T (1, 0), C (1.5, 0.5), S (3, 1.5), -C (2.5, 1), as the formula reads.
  EXPECT_NEAR(m.texcoords[0].x, 2.5f, 1e-6f);
  EXPECT_NEAR(m.texcoords[0].y, 1.0f, 1e-6f);
}

// An ElevationGrid's default texture coordinates (made by the geometry
// reader): s along x, t along z.
TEST(FlattenVrml97, ElevationGridTextureCoordinates) {
  const FlatVrml97 f = flat(
      "Shape { appearance Appearance { texture ImageTexture { url \"g.png\" } } "
      "geometry ElevationGrid { xDimension 3 zDimension 2 height [0 0 0 0 0 0] } }");
  const TriangleMesh& m = f.flat.mesh;
  ASSERT_EQ(m.triangle_count(), 4u);
  ASSERT_EQ(m.texcoords.size(), m.vertex_count());
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    EXPECT_FLOAT_EQ(m.texcoords[v].x, m.positions[v].x / 2) << v;
    EXPECT_FLOAT_EQ(m.texcoords[v].y, m.positions[v].z) << v;
  }
}

TEST(FlattenVrml97, WhatIsNotDrawnIsCounted) {
  const FlatVrml97 f = flat(
      "Inline { url \"x.wrl\" } Shape { geometry Text { string \"a\" } } "
      "Shape { geometry IndexedFaceSet { coord Coordinate { point [0 0 0] } coordIndex [0 1 2 -1] "
      "} }");
  EXPECT_EQ(f.shapes, 0u);
  EXPECT_EQ(f.skipped.at("Inline"), 1u);
  EXPECT_EQ(f.skipped.at("Text"), 1u);
  EXPECT_EQ(f.skipped.at("IndexedFaceSet"), 1u);  // an index out of range
}

// A skinned mesh is drawn in the pose its coordinates hold: Castle's Skin's
// shapes, an HAnimHumanoid's skin.
TEST(FlattenVrml97, SkinnedShapesAreDrawnInTheirStoredPose) {
  Log log;
  const auto x3d = [&](const std::string& body) {
    return flatten_vrml97(vrml97::read_vrml97("#X3D V4.0 utf8\nPROFILE Full\n" + body).scene, {},
                          log);
  };
  const FlatVrml97 skin = x3d(std::string("Skin { shapes [") + kQuad + "] }");
  EXPECT_EQ(skin.shapes, 1u);
  EXPECT_EQ(skin.flat.mesh.triangle_count(), 2u);
  const FlatVrml97 humanoid = x3d(std::string("HAnimHumanoid { skin [") + kQuad + "] }");
  EXPECT_EQ(humanoid.flat.mesh.triangle_count(), 2u);
}

// For the glTF output: each Shape drawn on its own, every level of a LOD
// (its empty last level too), IndexedLineSets as coloured segments.
TEST(FlattenVrml97, LodShapesKeepEveryLevelAndLines) {
  Log log;
  const auto r = vrml97::read_vrml97(std::string("#VRML V2.0 utf8\n") +
                                     "DEF L LOD { range [10] level [ " + kQuad + " Group {} ] }\n" +
                                     "Transform { translation 5 0 0 children [ " + kQuad +
                                     " Shape { appearance Appearance { material Material { "
                                     "emissiveColor 0 1 0 } } geometry IndexedLineSet { coord "
                                     "Coordinate { point [0 0 0, 1 0 0, 1 1 0] } coordIndex [0 1 2 "
                                     "-1 2 0] } } ] }");
  const Vrml97LodShapes shapes = vrml97_lod_shapes(r.scene, log);
  ASSERT_EQ(shapes.shapes.lods.size(), 1u);
  const scene::LodGroup& lod = shapes.shapes.lods.begin()->second;
  EXPECT_EQ(lod.lod->name, "L");
  ASSERT_EQ(lod.levels.size(), 2u);
  ASSERT_EQ(lod.levels[0].size(), 1u);
  EXPECT_EQ(lod.levels[0][0].surface.mesh.triangle_count(), 2u);
  EXPECT_TRUE(lod.levels[1].empty());
  ASSERT_EQ(shapes.shapes.plain.size(), 2u);
  EXPECT_EQ(shapes.shapes.plain[0].surface.mesh.positions[0], (Vec3{5, 0, 0}));
  const TriangleMesh& lines = shapes.shapes.plain[1].surface.mesh;
  EXPECT_EQ(lines.triangle_count(), 0u);
  EXPECT_EQ(lines.lines.size(), 3u);  // two segments, then one
  EXPECT_EQ(lines.colors.at(0), (Vec3{0, 1, 0}));
  // The one-surface flattening draws the lines too, in their colours.
  const FlatVrml97 flat = flatten_vrml97(r.scene, {}, log);
  EXPECT_EQ(flat.skipped.count("IndexedLineSet"), 0u);
  EXPECT_EQ(flat.flat.mesh.lines.size(), 3u);
  const Segment first = flat.flat.mesh.lines.front();
  EXPECT_EQ(flat.flat.mesh.colors.at(first[0]), (Vec3{0, 1, 0}));
  EXPECT_EQ(flat.flat.mesh.positions.size(), flat.flat.mesh.colors.size());
}

}  // namespace
}  // namespace lodforge
