// Open Inventor nodes in the traversal and the shape geometry, on tiny scenes:
// RotationXYZ, Array, MultipleCopy, Complexity, VertexProperty (as a node and
// as a field), BaseColor, the ignore flag, Switch's inherit, and the strip,
// quad-mesh and face-set shapes as triangles.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "lodforge/core/error.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/scene/flatten_scene.h"
#include "lodforge/scene/inventor_shapes.h"
#include "lodforge/scene/schema.h"
#include "lodforge/scene/statistics.h"
#include "lodforge/scene/tessellate_primitive.h"

namespace lodforge::scene {
namespace {

using ::testing::ElementsAre;

Scene iv(const std::string& body) {
  return vrml1::read_vrml1("#Inventor V2.1 ascii\n" + body, {.source_name = "t.iv"}).scene;
}

Box3 bounds(const TriangleMesh& m) {
  Box3 b;
  for (const auto& t : m.triangles)
    for (auto v : t) b.add(m.positions[v]);
  for (const auto& l : m.lines)
    for (auto v : l) b.add(m.positions[v]);
  return b;
}

void expect_box(const Box3& b, Vec3 lo, Vec3 hi) {
  EXPECT_NEAR(b.lo.x, lo.x, 1e-5);
  EXPECT_NEAR(b.lo.y, lo.y, 1e-5);
  EXPECT_NEAR(b.lo.z, lo.z, 1e-5);
  EXPECT_NEAR(b.hi.x, hi.x, 1e-5);
  EXPECT_NEAR(b.hi.y, hi.y, 1e-5);
  EXPECT_NEAR(b.hi.z, hi.z, 1e-5);
}

// Unit normal of a triangle of `m`.
Vec3 face_normal(const TriangleMesh& m, std::size_t t) {
  const auto& tri = m.triangles[t];
  return normalized(
      cross(m.positions[tri[1]] - m.positions[tri[0]], m.positions[tri[2]] - m.positions[tri[0]]));
}

TEST(InventorScene, RotationXyzRotatesAboutItsAxis) {
  // A 4 x 2 x 2 box turned a quarter about Z is 2 wide and 4 high.
  const TriangleMesh m =
      flatten_scene(iv("Separator { RotationXYZ { axis Z angle 1.5707963 } Cube { width 4 } }"));
  expect_box(bounds(m), {-1, -2, -1}, {1, 2, 1});
  const TriangleMesh y =
      flatten_scene(iv("Separator { RotationXYZ { axis Y angle 1.5707963 } Cube { width 4 } }"));
  expect_box(bounds(y), {-1, -1, -2}, {1, 1, 2});
}

TEST(InventorScene, ArrayDrawsItsChildrenOncePerInstance) {
  const TriangleMesh m =
      flatten_scene(iv("Separator { Array { numElements1 3 separation1 2 0 0 numElements2 2 "
                       "separation2 0 5 0  Cube { } } }"));
  EXPECT_EQ(m.triangle_count(), 6u * 12u);
  expect_box(bounds(m), {-1, -1, -1}, {5, 6, 1});
  // Centred, and the last instance at the origin.
  expect_box(bounds(flatten_scene(
                 iv("Array { origin CENTER numElements1 3 separation1 2 0 0 Cube { } }"))),
             {-3, -1, -1}, {3, 1, 1});
  expect_box(
      bounds(flatten_scene(iv("Array { origin LAST numElements1 3 separation1 2 0 0 Cube { } }"))),
      {-5, -1, -1}, {1, 1, 1});
  // Each instance saves the state: a Translation inside moves only its own.
  expect_box(bounds(flatten_scene(iv("Separator { Array { numElements1 2 separation1 10 0 0 "
                                     "Translation { translation 0 1 0 } Cube { } } Cube { } }"))),
             {-1, -1, -1}, {11, 2, 1});
  // A shape in an Array is one node met several times (one place).
  std::size_t visits = 0;
  std::set<std::size_t> places;
  traverse(iv("Array { numElements1 4 Cube { } }"), [&](const ShapeVisit& v) {
    ++visits;
    places.insert(v.child_index);
  });
  EXPECT_EQ(visits, 4u);
  EXPECT_EQ(places.size(), 1u);
}

TEST(InventorScene, ArraysOfAbsurdSizesAreErrors) {
  EXPECT_THROW(flatten_scene(iv("Array { numElements1 2000000000 Cube { } }")), DataError);
  EXPECT_THROW(flatten_scene(iv("Array { numElements1 2147483647 numElements2 2147483647 "
                                "numElements3 2147483647 Cube { } }")),
               DataError);
  EXPECT_THROW(flatten_scene(iv("Array { numElements1 1000 numElements2 1000 numElements3 2 "
                                "Cube { } }")),
               DataError);
  EXPECT_EQ(flatten_scene(iv("Array { numElements1 -5 Cube { } }")).triangle_count(), 0u);
}

TEST(InventorScene, MultipleCopyDrawsOncePerMatrix) {
  const TriangleMesh m =
      flatten_scene(iv("MultipleCopy { matrix [ 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1,"
                       " 1 0 0 0 0 1 0 0 0 0 1 0 10 0 0 1 ] Cube { } }"));
  EXPECT_EQ(m.triangle_count(), 24u);
  expect_box(bounds(m), {-1, -1, -1}, {11, 1, 1});
}

TEST(InventorScene, ComplexityChangesTheTessellationOfPrimitives) {
  auto triangles = [](const std::string& complexity, const char* shape) {
    return scene_statistics(iv("Separator { " + complexity + " " + shape + " }")).total_triangles;
  };
  for (const char* shape : {"Sphere { }", "Cone { }", "Cylinder { }"}) {
    const std::size_t none = triangles("", shape);
    EXPECT_EQ(triangles("Complexity { }", shape), none) << shape;  // default 0.5
    EXPECT_EQ(triangles("Complexity { value 0.5 }", shape), none) << shape;
    EXPECT_LT(triangles("Complexity { value 0 }", shape),
              triangles("Complexity { value 0.2 }", shape));
    EXPECT_LT(triangles("Complexity { value 0.2 }", shape), none) << shape;
    EXPECT_LT(none, triangles("Complexity { value 1 }", shape)) << shape;
    // Ignored, the value does not apply.
    EXPECT_EQ(triangles("Complexity { value 0 ~ }", shape), none) << shape;
  }
  // The segments follow the value; the default is the VRML 1.0 tessellation.
  EXPECT_EQ(segments_for_complexity(0.5f), 24);
  EXPECT_EQ(segments_for_complexity(0.f), 4);
  EXPECT_EQ(segments_for_complexity(1.f), 48);
  EXPECT_EQ(segments_for_complexity(7.f), 48);
  EXPECT_EQ(tessellate_primitive(Node{.type = "Cylinder"}).triangle_count(),
            tessellate_primitive(Node{.type = "Cylinder"}, {.segments = 24}).triangle_count());
  // A Cone with 4 segments: 4 side and 4 bottom triangles.
  EXPECT_EQ(triangles("Complexity { value 0 }", "Cone { }"), 8u);
  // Complexity is state: a Separator ends it.
  EXPECT_EQ(scene_statistics(iv("Separator { Separator { Complexity { value 0 } } Cone { } }"))
                .total_triangles,
            triangles("", "Cone { }"));
}

TEST(InventorScene, VertexPropertyGivesTheShapeItsVertices) {
  const Scene s = iv(R"(
    Separator {
      Coordinate3 { point [ 9 9 9, 9 9 9, 9 9 9 ] }
      IndexedFaceSet {
        vertexProperty VertexProperty {
          vertex [ 0 0 0, 2 0 0, 0 3 0 ]
          orderedRGBA [ 0xff0000ff, 0x00ff0080, 0x0000ffff ]
          materialBinding PER_VERTEX_INDEXED
        }
        coordIndex [ 0, 1, 2, -1 ]
      }
      IndexedFaceSet { coordIndex [ 0, 1, 2, -1 ] }
    })");
  std::vector<TriangleMesh> meshes;
  std::vector<const Node*> materials, bindings, coords;
  std::vector<TraversalState> states;  // a copy keeps the nodes made for the state
  traverse(s, [&](const ShapeVisit& v) {
    meshes.push_back(shape_mesh(v));
    materials.push_back(v.state.material);
    bindings.push_back(v.state.material_binding);
    coords.push_back(v.state.coordinate3);
    states.push_back(v.state);
  });
  ASSERT_EQ(meshes.size(), 2u);
  expect_box(bounds(meshes[0]), {0, 0, 0}, {2, 3, 0});
  // The property applies to its shape only.
  expect_box(bounds(meshes[1]), {9, 9, 9}, {9, 9, 9});
  EXPECT_EQ(materials[1], nullptr);
  // The colours are a Material for the readers of the state.
  ASSERT_NE(materials[0], nullptr);
  EXPECT_THAT(materials[0]->value("diffuseColor")->floats, ElementsAre(1, 0, 0, 0, 1, 0, 0, 0, 1));
  EXPECT_NEAR(materials[0]->value("transparency")->floats[1], 1 - 128 / 255.0, 1e-6);
  EXPECT_EQ(bindings[0]->value("value")->strings[0], "PER_VERTEX_INDEXED");
  EXPECT_EQ(coords[0]->value("point")->count(), 3u);
  // Empty fields set nothing: the Coordinate3 before stays.
  const Scene empty =
      iv("Separator { Coordinate3 { point [ 1 1 1, 2 2 2, 3 3 4 ] } IndexedFaceSet { "
         "vertexProperty VertexProperty { vertex [ ] } coordIndex [ 0, 1, 2, -1 ] } }");
  expect_box(bounds(flatten_scene(empty)), {1, 1, 1}, {3, 3, 4});
  // As a node of its own, a VertexProperty is state for the shapes after it.
  expect_box(bounds(flatten_scene(iv("Separator { VertexProperty { vertex [ 0 0 0, 5 0 0, 0 5 0 ] }"
                                     " FaceSet { numVertices 3 } }"))),
             {0, 0, 0}, {5, 5, 0});
}

TEST(InventorScene, BaseColorIsTheMaterial) {
  const Node* material = nullptr;
  TraversalState kept;
  traverse(iv("Separator { BaseColor { rgb [ 1 0 0, 0 0 1 ] } Cube { } }"),
           [&](const ShapeVisit& v) {
             material = v.state.material;
             kept = v.state;
           });
  ASSERT_NE(material, nullptr);
  EXPECT_EQ(material->type, "Material");
  EXPECT_THAT(material->value("diffuseColor")->floats, ElementsAre(1, 0, 0, 0, 0, 1));
}

TEST(InventorScene, IgnoredPropertiesAreNotApplied) {
  const Node* binding = nullptr;
  const Scene s =
      iv("Separator { MaterialBinding { value PER_FACE } MaterialBinding { value PER_VERTEX ~ }"
         " Cube { } }");
  traverse(s, [&](const ShapeVisit& v) { binding = v.state.material_binding; });
  ASSERT_NE(binding, nullptr);
  EXPECT_EQ(binding->value("value")->strings[0], "PER_FACE");
  expect_box(
      bounds(flatten_scene(iv("Separator { Translation { translation 5 0 0 ~ } Cube { } }"))),
      {-1, -1, -1}, {1, 1, 1});
  expect_box(
      bounds(flatten_scene(iv("Separator { Transform { translation 5 0 0 ~ scaleFactor 2 2 2 } "
                              "Cube { } }"))),
      {-2, -2, -2}, {2, 2, 2});
}

TEST(InventorScene, SwitchInheritTakesTheEnclosingChoice) {
  // Coin's switch.iv row 1: the inner Switch inherits 1 and draws its Sphere.
  const Scene s =
      iv("Switch { whichChild 1 Cube { } Switch { whichChild -2 Cube { } Sphere { } }"
         " Sphere { } }");
  std::vector<std::string> drawn;
  traverse(s, [&](const ShapeVisit& v) { drawn.push_back(v.shape.type); });
  EXPECT_THAT(drawn, ElementsAre("Sphere"));
  // Nothing to inherit: nothing drawn (Coin's faceset.iv keeps its FaceSet there).
  drawn.clear();
  traverse(iv("Switch { whichChild -2 Cube { } }"),
           [&](const ShapeVisit& v) { drawn.push_back(v.shape.type); });
  EXPECT_TRUE(drawn.empty());
}

TEST(InventorScene, LevelOfDetailTakesTheRequestedChild) {
  const Scene s = iv("LevelOfDetail { screenArea [ 100 ] Cube { } Sphere { } }");
  EXPECT_EQ(flatten_scene(s).triangle_count(), 12u);
  EXPECT_GT(flatten_scene(s, {.lod_level = 1}).triangle_count(), 12u);
  EXPECT_GT(flatten_scene(s, {.lod_level = 7}).triangle_count(), 12u);
}

constexpr const char* kStripCoords =
    "Coordinate3 { point [ 0 0 0, 0 1 0, 1 0 0, 1 1 0, 2 0 0, 2 1 0,  5 0 0, 5 1 0, 6 0 0 ] }";

TEST(InventorScene, TriangleStripSetGivesConsistentlyWoundTriangles) {
  const TriangleMesh m = flatten_scene(iv(std::string("Separator { ") + kStripCoords +
                                          " TriangleStripSet { numVertices [ 6, 3 ] } }"));
  ASSERT_EQ(m.triangle_count(), 4u + 1u);
  for (std::size_t t = 0; t < m.triangle_count(); ++t)
    EXPECT_NEAR(face_normal(m, t).z, -1, 1e-6) << t;  // all face the same way
  // startIndex skips coordinates; -1 takes the rest.
  EXPECT_EQ(flatten_scene(iv(std::string("Separator { ") + kStripCoords +
                             " TriangleStripSet { startIndex 3 numVertices -1 } }"))
                .triangle_count(),
            4u);
}

TEST(InventorScene, IndexedTriangleStripSetAndFaceSetAndQuadMesh) {
  const std::string c = std::string("Separator { ") + kStripCoords;
  EXPECT_EQ(
      flatten_scene(iv(c + " IndexedTriangleStripSet { coordIndex [ 0, 1, 2, 3, -1, 6, 7, 8 ] } }"))
          .triangle_count(),
      3u);
  EXPECT_EQ(flatten_scene(iv(c + " FaceSet { numVertices [ 4, 3 ] } }")).triangle_count(), 3u);
  // 3 rows of 3: 4 quads, 8 triangles, in the plane z = 0.
  const TriangleMesh q = flatten_scene(
      iv("Separator { Coordinate3 { point [ 0 0 0, 1 0 0, 2 0 0, 0 1 0, 1 1 0, 2 1 0, 0 2 0, "
         "1 2 0, 2 2 0 ] } QuadMesh { verticesPerRow 3 verticesPerColumn 3 } }"));
  EXPECT_EQ(q.triangle_count(), 8u);
  for (std::size_t t = 0; t < q.triangle_count(); ++t) EXPECT_NEAR(face_normal(q, t).z, 1, 1e-6);
  expect_box(bounds(q), {0, 0, 0}, {2, 2, 0});
  // LineSet: polylines.
  const TriangleMesh l = flatten_scene(iv(c + " LineSet { numVertices [ 3, 2 ] } }"));
  EXPECT_EQ(l.lines.size(), 2u + 1u);
  EXPECT_EQ(l.triangle_count(), 0u);
  // The statistics see them too.
  const SceneStatistics st = scene_statistics(iv(c + " FaceSet { numVertices [ 4, 3 ] } }"));
  EXPECT_EQ(st.total_triangles, 3u);
  EXPECT_EQ(st.node_counts.at("FaceSet"), 1u);
}

TEST(InventorScene, StripAttributesFollowInventorsBindings) {
  // Per vertex: the strip's own vertex numbers; per part: per strip; per
  // face: per triangle.
  auto equivalent = [](const std::string& binding, const char* shape) {
    const Scene s = iv(std::string("Separator { ") + kStripCoords +
                       " Material { diffuseColor [ 1 0 0, 0 1 0, 0 0 1, 1 1 0, 1 0 1, 0 1 1, "
                       "1 1 1, 0 0 0, 0.5 0.5 0.5 ] } MaterialBinding { value " +
                       binding + " } " + shape + " }");
    IndexedEquivalent out;
    traverse(s, [&](const ShapeVisit& v) { out = to_indexed_shape(v); });
    return out;
  };
  const char* strips = "TriangleStripSet { startIndex 1 numVertices [ 4, 3 ] }";
  IndexedEquivalent v = equivalent("PER_VERTEX", strips);
  EXPECT_THAT(v.shape->value("coordIndex")->ints,
              ElementsAre(1, 2, 3, -1, 3, 2, 4, -1, 5, 6, 7, -1));
  EXPECT_THAT(v.shape->value("materialIndex")->ints,
              ElementsAre(0, 1, 2, -1, 2, 1, 3, -1, 4, 5, 6, -1));
  EXPECT_EQ(v.state.material_binding->value("value")->strings[0], "PER_VERTEX_INDEXED");
  EXPECT_THAT(equivalent("PER_PART", strips).shape->value("materialIndex")->ints,
              ElementsAre(0, 0, 1));
  IndexedEquivalent f = equivalent("PER_FACE_INDEXED", strips);
  EXPECT_THAT(f.shape->value("materialIndex")->ints, ElementsAre(0, 1, 2));
  EXPECT_EQ(f.state.material_binding->value("value")->strings[0], "PER_FACE_INDEXED");
  // The indexed strip set reads materialIndex under an indexed binding.
  IndexedEquivalent ix = equivalent(
      "PER_VERTEX_INDEXED",
      "IndexedTriangleStripSet { coordIndex [ 0, 1, 2, 3 ] materialIndex [ 8, 7, 6, 5 ] }");
  EXPECT_THAT(ix.shape->value("materialIndex")->ints, ElementsAre(8, 7, 6, -1, 6, 7, 5, -1));
  // OVERALL: the state's binding, no index.
  IndexedEquivalent o = equivalent("OVERALL", strips);
  EXPECT_EQ(o.shape->value("materialIndex"), nullptr);
}

TEST(InventorScene, ShapesNeedingMissingCoordinatesAreErrorsWithTheLine) {
  const Scene s =
      iv("Separator {\n Coordinate3 { point [ 0 0 0, 1 0 0, 0 1 0 ] }\n"
         " TriangleStripSet { numVertices 5 } }");
  try {
    flatten_scene(s);
    FAIL() << "no error";
  } catch (const DataError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("line 4: TriangleStripSet uses coordinates 0..4"));
  }
}

}  // namespace
}  // namespace lodforge::scene
