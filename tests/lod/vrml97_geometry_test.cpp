// The polygons and mesh of VRML97 / X3D geometry nodes: corner tuples of
// each node type, attribute bindings, the mesh's vertices per distinct tuple,
// and what a bad index does.
#include "lodforge/lod/vrml97_geometry.h"

#include <gtest/gtest.h>

#include <string>

#include "lodforge/io/vrml97/read_vrml97.h"

namespace lodforge::vrml97_geometry {
namespace {

// The geometry node of the first Shape of `body` (an X3D classic scene, so
// the X3D-only geometry nodes read too), kept alive with its scene.
struct Geometry {
  vrml97::ReadResult read;
  NodePtr node;
  Log log;
  Polygons polygons;
  bool ok = false;
  ShapeMesh mesh;

  explicit Geometry(const std::string& geometry) {
    read = vrml97::read_vrml97("#X3D V3.0 utf8\nShape { geometry " + geometry + " }\n");
    node = node_of(*read.scene.roots.at(0), "geometry");
    GeometryReader reader(*node, log, "t.x3dv");
    ok = reader.read(polygons);
    if (ok) build_mesh(polygons, reader, {}, mesh);
  }

  std::string warnings() const {
    std::string all;
    for (const auto& d : log.entries()) all += d.text + "\n";
    return all;
  }
};

constexpr std::uint32_t kNo = kNone;

TEST(Vrml97Geometry, IndexedFaceSetFacesAndTheirCorners) {
  const Geometry g(
      "IndexedFaceSet { coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0, 2 0 0] } "
      "coordIndex [0 1 2 3 -1 1 4 2] }");  // a quad, then a triangle without its -1
  ASSERT_TRUE(g.ok) << g.warnings();
  EXPECT_EQ(g.polygons.start, (std::vector<std::uint32_t>{0, 4, 7}));
  ASSERT_EQ(g.polygons.corners.size(), 7u);
  EXPECT_EQ(g.polygons.corners[0], (Corner{0, kNo, kNo, kNo}));
  EXPECT_EQ(g.polygons.corners[5], (Corner{4, kNo, kNo, kNo}));
  // The quad is two triangles, the triangle one; coordinates 1 and 2 are
  // shared corners with the same tuple, so one vertex each.
  EXPECT_EQ(g.mesh.mesh.triangle_count(), 3u);
  EXPECT_EQ(g.mesh.mesh.positions.size(), 5u);
  EXPECT_EQ(g.mesh.triangle_polygon, (std::vector<std::uint32_t>{0, 0, 1}));
  EXPECT_EQ(g.mesh.mesh.positions[g.mesh.mesh.triangles[2][1]], (Vec3{2, 0, 0}));
}

TEST(Vrml97Geometry, AttributesPerVertexMakeVerticesAndPerFaceStayWithTheFace) {
  // Normals per corner by normalIndex: coordinate 0 takes two normals, so it
  // becomes two vertices. Colours per face (colorPerVertex FALSE).
  const Geometry g(
      "IndexedFaceSet { coord Coordinate { point [0 0 0, 1 0 0, 0 1 0, 0 0 1] } "
      "coordIndex [0 1 2 -1 0 2 3 -1] "
      "normal Normal { vector [0 0 1, 1 0 0] } normalIndex [0 0 0 -1 1 1 1 -1] "
      "color Color { color [1 0 0, 0 1 0] } colorPerVertex FALSE colorIndex [1 0] }");
  ASSERT_TRUE(g.ok) << g.warnings();
  EXPECT_EQ(g.polygons.corners[0], (Corner{0, 0, kNo, kNo}));
  EXPECT_EQ(g.polygons.corners[3], (Corner{0, 1, kNo, kNo}));
  EXPECT_EQ(g.polygons.face_color, (std::vector<std::uint32_t>{1, 0}));
  EXPECT_EQ(g.polygons.face_normal, (std::vector<std::uint32_t>{kNo, kNo}));
  EXPECT_EQ(g.mesh.mesh.positions.size(), 6u);  // corners 0 and 2 split by their normals
  const Vec3 point[] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (std::size_t v = 0; v < g.mesh.vertex_corner.size(); ++v)
    EXPECT_EQ(g.mesh.mesh.positions[v], point[g.mesh.vertex_corner[v][0]]);
}

TEST(Vrml97Geometry, TriangleAndQuadSets) {
  const std::string points = "coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] }";
  const Geometry its("IndexedTriangleSet { index [0 1 2 0 2 3] " + points + " }");
  ASSERT_TRUE(its.ok) << its.warnings();
  EXPECT_EQ(corners_per_face(*its.node), 3u);
  EXPECT_EQ(its.polygons.start.size(), 3u);
  EXPECT_EQ(its.mesh.mesh.triangle_count(), 2u);

  // A TriangleSet takes its coordinates in order; a partial last face is left out.
  const Geometry ts(
      "TriangleSet { coord Coordinate { point [0 0 0, 1 0 0, 0 1 0, 5 5 5, 6 5 5] } }");
  ASSERT_TRUE(ts.ok) << ts.warnings();
  EXPECT_EQ(set_corner_order(*ts.node), (std::vector<std::int32_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(ts.mesh.mesh.triangle_count(), 1u);

  const Geometry iqs("IndexedQuadSet { index [0 1 2 3] " + points +
                     " color Color { color [1 0 0, 0 1 0, 0 0 1, 1 1 1] } }");
  ASSERT_TRUE(iqs.ok) << iqs.warnings();
  EXPECT_EQ(corners_per_face(*iqs.node), 4u);
  EXPECT_EQ(iqs.polygons.corners[3], (Corner{3, kNo, kNo, 3}));  // colours indexed as coordinates
  EXPECT_EQ(iqs.mesh.mesh.triangle_count(), 2u);
}

TEST(Vrml97Geometry, ElevationGridIsQuadsWithDefaultTextureCoordinates) {
  const Geometry g(
      "ElevationGrid { xDimension 3 zDimension 2 xSpacing 2 zSpacing 0.5 "
      "height [0 1 2, 3 4 5] }");
  ASSERT_TRUE(g.ok) << g.warnings();
  EXPECT_EQ(g.polygons.start.size(), 3u);  // two quads
  EXPECT_EQ(g.mesh.mesh.triangle_count(), 4u);
  // Quad (x, z), (x, z+1), (x+1, z+1), (x+1, z); the texture coordinate of a
  // vertex is its own number.
  EXPECT_EQ(g.polygons.corners[1], (Corner{3, kNo, 3, kNo}));
  const Box3 b = g.mesh.mesh.bounds();
  EXPECT_FLOAT_EQ(b.hi.x, 4);
  EXPECT_FLOAT_EQ(b.hi.y, 5);
  EXPECT_FLOAT_EQ(b.hi.z, 0.5f);
}

TEST(Vrml97Geometry, BadIndicesLeaveTheShapeOrDropTheAttribute) {
  // A coordinate index out of range: the shape is not read, with a warning.
  const Geometry coords(
      "IndexedFaceSet { coord Coordinate { point [0 0 0, 1 0 0, 0 1 0] } coordIndex [0 1 7 -1] }");
  EXPECT_FALSE(coords.ok);
  EXPECT_NE(coords.warnings().find("7"), std::string::npos) << coords.warnings();
  const Geometry set(
      "IndexedTriangleSet { index [0 1 9] coord Coordinate { point [0 0 0, 1 0 0, "
      "0 1 0] } }");
  EXPECT_FALSE(set.ok);
  EXPECT_NE(set.warnings().find("index 9 out of range (3 coordinates)"), std::string::npos)
      << set.warnings();
  // A normal index out of range: the shape reads, without its normals.
  const Geometry normals(
      "IndexedFaceSet { coord Coordinate { point [0 0 0, 1 0 0, 0 1 0] } coordIndex [0 1 2 -1] "
      "normal Normal { vector [0 0 1] } normalIndex [0 0 5 -1] }");
  ASSERT_TRUE(normals.ok);
  EXPECT_NE(normals.warnings().find("the levels have no normals"), std::string::npos)
      << normals.warnings();
  for (const Corner& c : normals.polygons.corners) EXPECT_EQ(c[1], kNo);
  EXPECT_EQ(normals.mesh.mesh.triangle_count(), 1u);
}

}  // namespace
}  // namespace lodforge::vrml97_geometry
