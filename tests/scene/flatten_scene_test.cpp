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

// ---- Appearance: colours, opacity, texture coordinates ----

// The colour of each triangle's first corner.
std::vector<Vec3> triangle_colors(const TriangleMesh& m) {
  std::vector<Vec3> out;
  for (const auto& t : m.triangles) out.push_back(m.colors[t[0]]);
  return out;
}

TEST(FlattenScene, PlainSceneHasNoAppearance) {
  const vrml1::ReadResult r = vrml1::read_vrml1("#VRML V1.0 ascii\nSeparator { Cube {} }");
  const FlatScene flat = flatten_scene_appearance(r.scene);
  EXPECT_EQ(flat.mesh.triangle_count(), 12u);
  EXPECT_FALSE(flat.mesh.has_colors());
  EXPECT_FALSE(flat.mesh.has_texcoords());
  EXPECT_TRUE(flat.opacity.empty());
  EXPECT_TRUE(flat.textures.empty());
}

TEST(FlattenScene, PerFaceMaterialsColourTheirFaces) {
  // Two squares sharing an edge: red and blue. The shared corners are split.
  const vrml1::ReadResult r = vrml1::read_vrml1(R"(#VRML V1.0 ascii
Separator {
  Material { diffuseColor [1 0 0, 0 0 1] }
  MaterialBinding { value PER_FACE }
  Coordinate3 { point [-2 -1 0, 0 -1 0, 0 1 0, -2 1 0, 2 -1 0, 2 1 0] }
  IndexedFaceSet { coordIndex [0, 1, 2, 3, -1, 1, 4, 5, 2, -1] }
})");
  const FlatScene flat = flatten_scene_appearance(r.scene);
  ASSERT_EQ(flat.mesh.triangle_count(), 4u);
  EXPECT_EQ(flat.mesh.vertex_count(), 8u);
  const std::vector<Vec3> c = triangle_colors(flat.mesh);
  EXPECT_EQ(c[0], (Vec3{1, 0, 0}));
  EXPECT_EQ(c[1], (Vec3{1, 0, 0}));
  EXPECT_EQ(c[2], (Vec3{0, 0, 1}));
  EXPECT_EQ(c[3], (Vec3{0, 0, 1}));
  // Every corner of a face has the face's colour.
  for (const auto& t : flat.mesh.triangles)
    EXPECT_EQ(flat.mesh.colors[t[1]], flat.mesh.colors[t[0]]);
  // The plain flattening is unchanged: shared corners, no colours.
  EXPECT_EQ(flatten_scene(r.scene).vertex_count(), 6u);
  EXPECT_FALSE(flatten_scene(r.scene).has_colors());
}

TEST(FlattenScene, IndexedBindingsEmissiveAndTransparency) {
  const vrml1::ReadResult r = vrml1::read_vrml1(R"(#VRML V1.0 ascii
Separator {
  Material { diffuseColor [0.5 0 0, 0 0.5 0] emissiveColor [0 0 0.25] transparency [0, 0.75] }
  Coordinate3 { point [0 0 0, 1 0 0, 0 1 0, 1 1 0] }
  Separator {
    MaterialBinding { value PER_FACE_INDEXED }
    IndexedFaceSet { coordIndex [0, 1, 2, -1, 1, 3, 2, -1] materialIndex [1, 0] }
  }
  MaterialBinding { value PER_VERTEX_INDEXED }
  IndexedFaceSet { coordIndex [0, 1, 2, -1] materialIndex [0, 1, 1] }
  Sphere {}
})");
  const FlatScene flat = flatten_scene_appearance(r.scene);
  const std::vector<Vec3> c = triangle_colors(flat.mesh);
  ASSERT_GE(c.size(), 3u);
  // Diffuse + emissive (the emissive list repeats its one value).
  EXPECT_EQ(c[0], (Vec3{0, 0.5f, 0.25f}));
  EXPECT_EQ(c[1], (Vec3{0.5f, 0, 0.25f}));
  const Triangle& t = flat.mesh.triangles[2];
  EXPECT_EQ(flat.mesh.colors[t[0]], (Vec3{0.5f, 0, 0.25f}));
  EXPECT_EQ(flat.mesh.colors[t[1]], (Vec3{0, 0.5f, 0.25f}));
  EXPECT_FLOAT_EQ(flat.opacity[t[0]], 1.f);
  EXPECT_FLOAT_EQ(flat.opacity[t[1]], 0.25f);
  // The primitive takes the first row.
  const Triangle& sphere = flat.mesh.triangles.back();
  EXPECT_EQ(flat.mesh.colors[sphere[0]], (Vec3{0.5f, 0, 0.25f}));
}

TEST(FlattenScene, InventorPackedColoursPerFace) {
  const vrml1::ReadResult r = vrml1::read_vrml1(R"(#Inventor V2.1 ascii
Separator {
  FaceSet {
    vertexProperty VertexProperty {
      vertex [0 0 0, 1 0 0, 0 1 0, 2 0 0, 3 0 0, 2 1 0]
      orderedRGBA [0xff0000ff, 0x00ff00ff]
      materialBinding PER_FACE
    }
    numVertices [3, 3]
  }
})");
  const std::vector<Vec3> c = triangle_colors(flatten_scene_appearance(r.scene).mesh);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0], (Vec3{1, 0, 0}));
  EXPECT_EQ(c[1], (Vec3{0, 1, 0}));
}

TEST(FlattenScene, TexturesAndTheirCoordinates) {
  const vrml1::ReadResult r = vrml1::read_vrml1(R"(#VRML V1.0 ascii
Separator {
  DEF T Texture2 { image 1 1 3 0xff0000 wrapS CLAMP }
  Coordinate3 { point [0 0 0, 4 0 0, 4 2 0, 0 2 0] }
  IndexedFaceSet { coordIndex [0, 1, 2, 3, -1] }
  TextureCoordinate2 { point [0 0, 2 0, 2 2, 0 2] }
  IndexedFaceSet { coordIndex [0, 1, 2, 3, -1] textureCoordIndex [3, 2, 1, 0, -1] }
  Texture2 { filename "wood.jpg" }
  Cube {}
  Texture2 {}
  Cube {}
})");
  const FlatScene flat = flatten_scene_appearance(r.scene);
  ASSERT_EQ(flat.textures.size(), 2u);
  EXPECT_EQ(flat.textures[0].image, (std::vector<std::int32_t>{1, 1, 3, 0xff0000}));
  EXPECT_FALSE(flat.textures[0].repeat_s);
  EXPECT_TRUE(flat.textures[0].repeat_t);
  EXPECT_EQ(flat.textures[1].filename, "wood.jpg");
  const TriangleMesh& m = flat.mesh;
  ASSERT_EQ(m.triangle_count(), 2u + 2u + 12u + 12u);
  ASSERT_EQ(m.texcoords.size(), m.vertex_count());
  // Default mapping: s along x (the longest side, 0..1), t along y (0..2/4).
  for (std::size_t f = 0; f < 2; ++f)
    for (auto v : m.triangles[f]) {
      EXPECT_FLOAT_EQ(m.texcoords[v].x, m.positions[v].x / 4);
      EXPECT_FLOAT_EQ(m.texcoords[v].y, m.positions[v].y / 4);
    }
  // textureCoordIndex: coordinate 0 takes texture coordinate 3.
  for (auto v : m.triangles[2])
    if (m.positions[v] == Vec3{0, 0, 0}) EXPECT_EQ(m.texcoords[v], (Vec2{0, 2}));
  EXPECT_EQ(m.materials[0], 0u);
  EXPECT_EQ(m.materials[2], 0u);
  EXPECT_EQ(m.materials[4], 1u);
  // An empty Texture2 turns texturing off.
  EXPECT_EQ(m.materials.back(), kUntextured);
}

// Texture2Transform moves the texture coordinates (scale and rotation about
// the center, then translation), accumulating as transforms do, within its
// Separator only.
TEST(FlattenScene, Texture2TransformMovesTextureCoordinatesAndAccumulates) {
  const vrml1::ReadResult r = vrml1::read_vrml1(R"(#VRML V1.0 ascii
Separator {
  Texture2 { filename "wood.jpg" }
  Coordinate3 { point [0 0 0, 1 0 0, 0 1 0] }
  TextureCoordinate2 { point [0 0, 1 0, 0 1] }
  Separator {
    Texture2Transform { translation 0.5 0.25 }
    IndexedFaceSet { coordIndex [0, 1, 2, -1] }
    Texture2Transform { scaleFactor 2 2 center 1 0 }
    IndexedFaceSet { coordIndex [0, 1, 2, -1] }
  }
  Texture2Transform { rotation 1.5707963 }
  IndexedFaceSet { coordIndex [0, 1, 2, -1] }
})");
  const FlatScene flat = flatten_scene_appearance(r.scene);
  const TriangleMesh& m = flat.mesh;
  ASSERT_EQ(m.triangle_count(), 3u);
  auto uv_at = [&](std::size_t f, const Vec3& p) {
    for (auto v : m.triangles[f])
      if (m.positions[v] == p) return m.texcoords[v];
    ADD_FAILURE() << "no corner at that point";
    return Vec2{};
  };
  // Translated.
  EXPECT_NEAR(uv_at(0, {1, 0, 0}).x, 1.5f, 1e-6f);
  EXPECT_NEAR(uv_at(0, {1, 0, 0}).y, 0.25f, 1e-6f);
  // Translated, then (first applied) scaled by 2 about (1, 0): (0, 1) -> (-1, 2) -> (-0.5, 2.25).
  EXPECT_NEAR(uv_at(1, {0, 1, 0}).x, -0.5f, 1e-6f);
  EXPECT_NEAR(uv_at(1, {0, 1, 0}).y, 2.25f, 1e-6f);
  // Outside the Separator only the rotation by pi/2: (1, 0) -> (0, 1).
  EXPECT_NEAR(uv_at(2, {1, 0, 0}).x, 0.0f, 1e-6f);
  EXPECT_NEAR(uv_at(2, {1, 0, 0}).y, 1.0f, 1e-6f);
}

}  // namespace
}  // namespace lodforge::scene
