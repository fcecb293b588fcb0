#include "lodforge/lod/shape_geometry.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "lodforge/core/error.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/scene/traverse.h"

namespace lodforge {
namespace {

/// Reads the first IndexedFaceSet / IndexedLineSet of a VRML 1.0 text.
struct ReadShape {
  explicit ReadShape(const std::string& body, ShapeGeometryOptions options = {}) {
    scene = vrml1::read_vrml1("#VRML V1.0 ascii\nSeparator {\n" + body + "\n}\n").scene;
    bool done = false;
    scene::traverse(scene, [&](const scene::ShapeVisit& v) {
      if (done || (v.shape.type != "IndexedFaceSet" && v.shape.type != "IndexedLineSet")) return;
      done = true;
      geometry = read_shape_geometry(v, options, log);
      state = v.state;
    });
    EXPECT_TRUE(done);
  }
  scene::Scene scene;
  ShapeGeometry geometry;
  scene::TraversalState state;
  Log log;
};

constexpr const char* kSquare = "Coordinate3 { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] }\n";

TEST(ShapeGeometry, TrianglesKeepTheirCornersAndPolygons) {
  ReadShape r(std::string(kSquare) + "IndexedFaceSet { coordIndex [0, 1, 2, -1, 0, 2, 3, -1] }");
  const ShapeGeometry& g = r.geometry;
  EXPECT_EQ(g.mesh.positions.size(), 4u);
  ASSERT_EQ(g.mesh.triangles.size(), 2u);
  EXPECT_EQ(g.triangle_polygon, (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(g.input_faces, 2u);
  EXPECT_EQ(g.dropped_faces, 0u);
  EXPECT_EQ(g.material_binding, AttributeBinding::kNone);
  EXPECT_FALSE(g.has_texcoords);
  EXPECT_FALSE(g.repaired);
}

TEST(ShapeGeometry, AQuadIsTwoTrianglesOfOnePolygonMarkedQuad) {
  ReadShape r(std::string(kSquare) + "IndexedFaceSet { coordIndex [0, 1, 2, 3, -1] }");
  const ShapeGeometry& g = r.geometry;
  ASSERT_EQ(g.mesh.triangles.size(), 2u);
  EXPECT_EQ(g.triangle_polygon, (std::vector<std::uint32_t>{0, 0}));
  ASSERT_EQ(g.polygon_is_quad.size(), 1u);
  EXPECT_TRUE(g.polygon_is_quad[0]);
}

TEST(ShapeGeometry, AFaceWithFewerThanThreeDistinctCornersIsDropped) {
  ReadShape r(std::string(kSquare) + "IndexedFaceSet { coordIndex [0, 1, 2, -1, 3, 3, 3, -1] }");
  EXPECT_EQ(r.geometry.mesh.triangles.size(), 1u);
  EXPECT_EQ(r.geometry.input_faces, 2u);
  EXPECT_EQ(r.geometry.dropped_faces, 1u);
}

TEST(ShapeGeometry, ACornerWithAnotherTexCoordSplitsTheVertex) {
  // Coordinate 0 is used with texture coordinate 0 by the first triangle and
  // with 1 by the second: a seam, so two mesh vertices share its position.
  ReadShape r(std::string(kSquare) +
              "TextureCoordinate2 { point [0 0, 1 0, 1 1, 0 1] }\n"
              "IndexedFaceSet { coordIndex [0, 1, 2, -1, 0, 2, 3, -1]\n"
              "  textureCoordIndex [0, 1, 2, -1, 1, 2, 3, -1] }");
  const ShapeGeometry& g = r.geometry;
  EXPECT_TRUE(g.has_texcoords);
  EXPECT_EQ(g.mesh.positions.size(), 5u);
  ASSERT_EQ(g.vertex_texcoord.size(), 5u);
  EXPECT_EQ(g.texcoord_values.size(), 4u);
  for (std::size_t v = 0; v < g.mesh.positions.size(); ++v)
    for (std::size_t w = v + 1; w < g.mesh.positions.size(); ++w)
      if (g.mesh.positions[v] == g.mesh.positions[w])
        EXPECT_NE(g.vertex_texcoord[v], g.vertex_texcoord[w]);
}

TEST(ShapeGeometry, PerFaceMaterialsFollowTheTriangles) {
  ReadShape r(std::string(kSquare) +
              "Material { diffuseColor [1 0 0, 0 0 1] }\nMaterialBinding { value PER_FACE }\n"
              "IndexedFaceSet { coordIndex [0, 1, 2, -1, 0, 2, 3, -1] }");
  const ShapeGeometry& g = r.geometry;
  EXPECT_EQ(g.material_binding, AttributeBinding::kPerFace);
  ASSERT_EQ(g.mesh.materials.size(), 2u);
  EXPECT_NE(g.mesh.materials[0], g.mesh.materials[1]);
  ASSERT_TRUE(g.material);
}

TEST(ShapeGeometry, ACoordIndexOutOfRangeIsADataErrorWithItsLine) {
  EXPECT_THAT(
      [] { ReadShape r(std::string(kSquare) + "IndexedFaceSet { coordIndex [0, 1, 7, -1] }"); },
      ::testing::ThrowsMessage<DataError>(::testing::HasSubstr("line")));
}

TEST(ShapeGeometry, AnAttributeIndexOutOfRangeDropsTheAttributeWithAWarning) {
  ReadShape r(std::string(kSquare) +
              "TextureCoordinate2 { point [0 0, 1 0] }\n"
              "IndexedFaceSet { coordIndex [0, 1, 2, -1] textureCoordIndex [0, 1, 9, -1] }");
  EXPECT_FALSE(r.geometry.has_texcoords);
  EXPECT_TRUE(r.geometry.repaired);
  EXPECT_GE(r.log.count(LogLevel::kWarning), 1u);
}

TEST(ShapeGeometry, ALineSetBecomesSegments) {
  ReadShape r(std::string(kSquare) + "IndexedLineSet { coordIndex [0, 1, 2, 3, -1] }");
  EXPECT_TRUE(r.geometry.mesh.triangles.empty());
  EXPECT_EQ(r.geometry.mesh.lines.size(), 3u);
}

/// The text of one level node as the writer prints it.
std::string text_of(const scene::NodePtr& level) {
  scene::Scene s;
  s.roots.push_back(level);
  return vrml1::write_vrml1(s);
}

TEST(LevelWriter, LevelsShareOneCoordinate3AndAppendOnlyMovedPositions) {
  ReadShape r(std::string(kSquare) + "IndexedFaceSet { coordIndex [0, 1, 2, -1, 0, 2, 3, -1] }");
  const ShapeGeometry& g = r.geometry;
  LevelWriter writer(g, r.state, /*no_lines=*/false);
  scene::NodePtr level0 = writer.level(g.mesh, {}, {});
  // A coarser level: one triangle, of vertices 0 and 2 left in place and a
  // new position for the third corner.
  TriangleMesh coarse;
  coarse.positions = {g.mesh.positions[0], g.mesh.positions[2], {0.5f, 2, 0}};
  coarse.triangles = {{0, 1, 2}};
  scene::NodePtr level1 = writer.level(coarse, {0, 2, 3}, {1});
  const std::string t1 = text_of(level1);
  // Both levels hold the same Coordinate3 node, with the 4 input points and
  // the one moved point appended.
  auto coordinate_of = [](const scene::NodePtr& level) -> const scene::Node* {
    for (const auto& c : level->children)
      if (c->type == "Coordinate3") return c.get();
    return nullptr;
  };
  ASSERT_TRUE(coordinate_of(level0));
  EXPECT_EQ(coordinate_of(level0), coordinate_of(level1));
  EXPECT_EQ(coordinate_of(level1)->value("point")->floats.size(), 5u * 3);
  EXPECT_THAT(t1, ::testing::HasSubstr("IndexedFaceSet"));
}

}  // namespace
}  // namespace lodforge
