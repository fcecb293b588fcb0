// Open Inventor 2.x ASCII in the reader and the writer, on tiny scenes written
// here: SFNode fields (vertexProperty), packed colours, the ignore flag `~`,
// field connections, the Inventor nodes of the schema, what stays unknown,
// and that none of it leaks into VRML 1.0 files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lodforge/core/error.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/scene/schema.h"
#include "vrml1/corpus.h"

namespace lodforge::vrml1 {
namespace {

using scene::FieldKind;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

ReadResult parse_iv(const std::string& body) {
  return read_vrml1("#Inventor V2.1 ascii\n" + body, {.source_name = "t.iv"});
}

std::string error_of(const std::string& text) {
  try {
    read_vrml1(text, {.source_name = "t.iv"});
  } catch (const ParseError& e) {
    return e.what();
  }
  return "no error";
}

// Written and read again: the same graph.
void expect_round_trip(const scene::Scene& s) {
  const std::string text = write_vrml1(s);
  const ReadResult again = read_vrml1(text, {.source_name = "again.iv"});
  EXPECT_TRUE(scene::equal(s, again.scene)) << text;
  EXPECT_EQ(write_vrml1(again.scene), text);
}

TEST(InventorRead, VertexPropertyIsANodeInAField) {
  auto r = parse_iv(R"(
    Separator {
      IndexedFaceSet {
        vertexProperty VertexProperty {
          vertex [ 0 0 0, 1 0 0, 0 1 0 ]
          normal [ ]
          orderedRGBA [ 0xff0000ff, 0xff00ff, 0xffff ]
          materialBinding PER_VERTEX
        }
        coordIndex [ 0, 1, 2, -1 ]
      }
      IndexedLineSet { vertexProperty NULL coordIndex [ 0, 1 ] }
    })");
  EXPECT_TRUE(r.log.entries().empty());
  const scene::Node& ifs = *r.scene.roots.at(0)->children.at(0);
  ASSERT_EQ(ifs.type, "IndexedFaceSet");
  const scene::FieldValue* vp = ifs.value("vertexProperty");
  ASSERT_NE(vp, nullptr);
  EXPECT_EQ(vp->type.kind, FieldKind::kNode);
  ASSERT_EQ(vp->nodes.size(), 1u);
  const scene::Node& v = *vp->nodes[0];
  EXPECT_EQ(v.type, "VertexProperty");
  EXPECT_EQ(v.value("vertex")->count(), 3u);
  EXPECT_EQ(v.value("normal")->count(), 0u);
  EXPECT_EQ(v.value("orderedRGBA")->type.kind, FieldKind::kUInt32);
  EXPECT_THAT(v.value("orderedRGBA")->ints,
              ElementsAre(std::int32_t(0xff0000ffu), 0xff00ff, 0xffff));
  EXPECT_EQ(v.value("materialBinding")->strings[0], "PER_VERTEX");
  const scene::Node& ils = *r.scene.roots.at(0)->children.at(1);
  EXPECT_TRUE(ils.value("vertexProperty")->nodes.empty());  // NULL
  // Written as Inventor writes it: the node in place, colours in hexadecimal.
  const std::string text = write_vrml1(r.scene);
  EXPECT_THAT(text, HasSubstr("vertexProperty VertexProperty {"));
  EXPECT_THAT(text, HasSubstr("0xff0000ff"));
  EXPECT_THAT(text, HasSubstr("vertexProperty NULL"));
  EXPECT_TRUE(text.starts_with("#Inventor V2.1 ascii\n"));
  expect_round_trip(r.scene);
}

TEST(InventorRead, SharedVertexPropertyKeepsItsSharing) {
  auto r = parse_iv(R"(
    Separator {
      FaceSet { vertexProperty DEF vp VertexProperty { vertex [ 0 0 0, 1 0 0, 0 1 0 ] }
                numVertices 3 }
      TriangleStripSet { vertexProperty USE vp numVertices 3 }
    })");
  const auto& kids = r.scene.roots.at(0)->children;
  EXPECT_EQ(kids[0]->value("vertexProperty")->nodes[0], kids[1]->value("vertexProperty")->nodes[0]);
  const std::string text = write_vrml1(r.scene);
  EXPECT_THAT(text, HasSubstr("USE vp"));
  expect_round_trip(r.scene);
  // A copy of the graph copies the field's node once.
  std::unordered_map<const scene::Node*, scene::NodePtr> done;
  scene::NodePtr copy = scene::copy_subtree(r.scene.roots[0], done);
  EXPECT_NE(copy->children[0]->value("vertexProperty")->nodes[0],
            kids[0]->value("vertexProperty")->nodes[0]);
  EXPECT_EQ(copy->children[0]->value("vertexProperty")->nodes[0],
            copy->children[1]->value("vertexProperty")->nodes[0]);
}

TEST(InventorRead, IgnoreFlagIsKeptAfterAValueOrInItsPlace) {
  auto r = parse_iv(R"(
    Separator {
      MaterialBinding { value PER_VERTEX_INDEXED ~ }
      Cone { parts BOTTOM ~ bottomRadius 0.5 }
      Cube { width ~ }
      Material { diffuseColor [ 1 0 0, 0 1 0 ] ~ }
    })");
  EXPECT_TRUE(r.log.entries().empty());
  const auto& kids = r.scene.roots.at(0)->children;
  const scene::Field* binding = kids[0]->find("value");
  ASSERT_NE(binding, nullptr);
  EXPECT_TRUE(binding->ignored);
  EXPECT_EQ(binding->value.strings[0], "PER_VERTEX_INDEXED");
  EXPECT_EQ(kids[0]->applied_value("value"), nullptr);  // what a traversal applies
  EXPECT_TRUE(kids[1]->find("parts")->ignored);
  EXPECT_FALSE(kids[1]->find("bottomRadius")->ignored);
  const scene::Field* width = kids[2]->find("width");
  EXPECT_TRUE(width->ignored);
  EXPECT_TRUE(width->no_value);
  EXPECT_FLOAT_EQ(width->value.floats.at(0), 2);  // the default
  EXPECT_TRUE(kids[3]->find("diffuseColor")->ignored);
  const std::string text = write_vrml1(r.scene);
  EXPECT_THAT(text, HasSubstr("value PER_VERTEX_INDEXED ~"));
  EXPECT_THAT(text, HasSubstr("parts BOTTOM ~"));
  EXPECT_THAT(text, HasSubstr("width ~\n"));
  expect_round_trip(r.scene);
}

TEST(InventorRead, FieldConnectionsAreKeptVerbatim) {
  // The Mentor's windmill: the blades' angle is connected to an engine.
  auto r = parse_iv(R"(
    Separator {
      RotationXYZ {
        axis Z
        angle 0 = ElapsedTime {
          speed 0.4
        }
        . timeOut
      }
      DEF t Translation { translation 1 0 0 }
      Translation { translation 0 0 0 = USE t.translation ~ }
      Cube { }
    })");
  const auto& kids = r.scene.roots.at(0)->children;
  const scene::Field* angle = kids[0]->find("angle");
  ASSERT_NE(angle, nullptr);
  EXPECT_FLOAT_EQ(angle->value.floats.at(0), 0);
  EXPECT_THAT(angle->connection, HasSubstr("ElapsedTime {"));
  EXPECT_TRUE(angle->connection.ends_with(". timeOut"));
  const scene::Field* tr = kids[2]->find("translation");
  EXPECT_EQ(tr->connection, "USE t.translation");
  EXPECT_TRUE(tr->ignored);
  EXPECT_EQ(kids.size(), 4u);  // the engine is no child
  const std::string text = write_vrml1(r.scene);
  EXPECT_THAT(text, HasSubstr("angle 0 = ElapsedTime {"));
  expect_round_trip(r.scene);
}

TEST(InventorRead, InventorNodesAreTyped) {
  auto r = parse_iv(R"(
    Separator {
      Complexity { type OBJECT_SPACE value 0.2 }
      RotationXYZ { axis Y angle 1.5 }
      BaseColor { rgb [ 1 0 0, 0 1 0 ] }
      Array { numElements1 3 separation1 2 0 0 origin CENTER Cube { } }
      MultipleCopy { matrix [ 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1,
                              1 0 0 0 0 1 0 0 0 0 1 0 5 0 0 1 ] Sphere { } }
      LevelOfDetail { screenArea [ 100 ] Cube { } Sphere { } }
      QuadMesh { verticesPerRow 2 verticesPerColumn 2 }
      TriangleStripSet { numVertices [ 3, 4 ] }
      IndexedTriangleStripSet { coordIndex [ 0, 1, 2, 3, -1 ] }
      DrawStyle { style LINES ~ }
    })");
  const auto& kids = r.scene.roots.at(0)->children;
  EXPECT_FLOAT_EQ(kids[0]->value("value")->floats[0], 0.2f);
  EXPECT_EQ(kids[1]->value("axis")->strings[0], "Y");
  EXPECT_EQ(kids[2]->value("rgb")->count(), 2u);
  EXPECT_EQ(kids[3]->children.size(), 1u);
  EXPECT_EQ(kids[4]->value("matrix")->count(), 2u);
  EXPECT_EQ(kids[5]->children.size(), 2u);
  EXPECT_EQ(kids[6]->value("verticesPerRow")->ints[0], 2);
  EXPECT_THAT(kids[7]->value("numVertices")->ints, ElementsAre(3, 4));
  EXPECT_EQ(kids[8]->value("coordIndex")->count(), 5u);
  // Inventor nodes without geometry stay unknown, kept verbatim.
  EXPECT_TRUE(kids[9]->is_raw);
  EXPECT_THAT(write_vrml1(r.scene), HasSubstr("DrawStyle { style LINES ~ }"));
  for (std::size_t i = 0; i < 9; ++i) EXPECT_FALSE(kids[i]->is_raw) << kids[i]->type;
  expect_round_trip(r.scene);
}

TEST(InventorRead, VrmlFilesDoNotKnowInventorNodesOrFields) {
  auto r = read_vrml1(
      "#VRML V1.0 ascii\nSeparator { Complexity { value 0 } Separator { "
      "renderCaching ON } }",
      {.source_name = "t.wrl"});
  const auto& kids = r.scene.roots.at(0)->children;
  EXPECT_TRUE(kids[0]->is_raw);                         // unknown node in VRML 1.0
  EXPECT_TRUE(kids[1]->find("renderCaching")->is_raw);  // unknown field in VRML 1.0
  EXPECT_EQ(write_vrml1(r.scene).substr(0, 17), "#VRML V1.0 ascii\n");
  // In an Inventor file both are typed.
  auto iv = parse_iv("Separator { Complexity { value 0 } Separator { renderCaching ON } }");
  EXPECT_FALSE(iv.scene.roots[0]->children[0]->is_raw);
  EXPECT_FALSE(iv.scene.roots[0]->children[1]->find("renderCaching")->is_raw);
}

TEST(InventorRead, ExtensionNodesMayDeclareNodeAndPackedColourFields) {
  auto r = parse_iv(
      "Torus { fields [ SFNode child, MFUInt32 colors, SFFloat r ] child Cube { } colors "
      "[ 0xff0000ff ] r 2 }");
  const scene::Node& t = *r.scene.roots.at(0);
  ASSERT_EQ(t.value("child")->nodes.size(), 1u);
  EXPECT_EQ(t.value("child")->nodes[0]->type, "Cube");
  EXPECT_THAT(t.value("colors")->ints, ElementsAre(std::int32_t(0xff0000ffu)));
  expect_round_trip(r.scene);
}

TEST(InventorRead, ErrorsNameFileLineAndColumn) {
  EXPECT_EQ(error_of("#Inventor V2.1 ascii\nRotationXYZ { axis W }"),
            "t.iv:2:20: expected one of X, Y, Z for field 'axis', got 'W'");
  EXPECT_EQ(error_of("#Inventor V2.1 ascii\nFaceSet { vertexProperty 3 }"),
            "t.iv:2:26: expected a node or NULL for field 'vertexProperty', got '3'");
  EXPECT_EQ(error_of("#Inventor V2.1 ascii\nFaceSet { vertexProperty USE nothing }"),
            "t.iv:2:30: USE of undefined node name 'nothing'");
  EXPECT_EQ(error_of("#Inventor V2.1 ascii\nRotationXYZ { angle 0 = ElapsedTime { } timeOut }"),
            "t.iv:2:41: expected '.' and a field name after the connection of 'angle', got "
            "'timeOut'");
  EXPECT_EQ(error_of("#Inventor V2.1 ascii\nQuadMesh { verticesPerRow 2.5 }"),
            "t.iv:2:27: expected an integer for SFLong field 'verticesPerRow', got '2.5'");
}

TEST(InventorRead, EveryCorpusFileReadsAndWritesBackTheSameGraph) {
  const auto files = testing::all_inventor_test_files();
  if (files.empty()) GTEST_SKIP() << "no shared corpus";
  for (const auto& path : files) {
    SCOPED_TRACE(path);
    const ReadResult r = read_vrml1_file(path);
    EXPECT_TRUE(scene::is_inventor_header(r.scene.header));
    expect_round_trip(r.scene);
  }
}

TEST(InventorRead, HeadersOfEveryInventorVersionAreKept) {
  for (const char* h : {"#Inventor V1.0 ascii", "#Inventor V2.0 ascii", "#Inventor V2.1 ascii"}) {
    auto r = read_vrml1(std::string(h) + "\nSeparator { Complexity { value 0 } }", {});
    EXPECT_EQ(r.scene.header, h);
    EXPECT_FALSE(r.scene.roots[0]->children[0]->is_raw) << h;
    EXPECT_TRUE(scene::is_inventor_header(r.scene.header));
  }
  EXPECT_FALSE(scene::is_inventor_header("#VRML V1.0 ascii"));
}

}  // namespace
}  // namespace lodforge::vrml1
