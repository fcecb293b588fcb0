// The VRML 1.0 reader on text written in the tests: every field type, DEF/USE,
// extension syntax, unknown nodes and fields, error messages, deep nesting.
#include "lodforge/io/vrml1/read_vrml1.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lodforge/core/error.h"
#include "lodforge/scene/schema.h"

namespace lodforge::vrml1 {
namespace {

using scene::FieldKind;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

ReadResult parse(const std::string& body) {
  return read_vrml1("#VRML V1.0 ascii\n" + body, {.source_name = "t.wrl"});
}

std::string error_of(const std::string& text) {
  try {
    read_vrml1(text, {.source_name = "t.wrl"});
  } catch (const ParseError& e) {
    return e.what();
  }
  return "no error";
}

const scene::Node& root(const ReadResult& r) {
  return *r.scene.roots.at(0);
}

TEST(ReadVrml1, FloatKindsAndTheirComponents) {
  auto r = parse(R"(
    Separator {
      Coordinate3 { point [ 1 2 3, -4.5e1 +5 .5, ] }
      Material { diffuseColor 1 0 0 shininess [0.1, 0.2] }
      MatrixTransform { matrix 1 0 0 0  0 1 0 0  0 0 1 0  7 8 9 1 }
      Rotation { rotation 0 1 0 1.5708 }
      Texture2Transform { translation 0.5 0.25 }
    })");
  const auto& s = root(r);
  ASSERT_EQ(s.children.size(), 5u);
  EXPECT_THAT(s.children[0]->value("point")->floats, ElementsAre(1, 2, 3, -45, 5, 0.5));
  EXPECT_EQ(s.children[0]->value("point")->count(), 2u);
  EXPECT_THAT(s.children[1]->value("diffuseColor")->floats, ElementsAre(1, 0, 0));
  EXPECT_EQ(s.children[1]->value("shininess")->count(), 2u);
  EXPECT_EQ(s.children[2]->value("matrix")->floats.size(), 16u);
  EXPECT_FLOAT_EQ(s.children[2]->value("matrix")->floats[13], 8);
  EXPECT_FLOAT_EQ(s.children[3]->value("rotation")->floats[3], 1.5708f);
  EXPECT_THAT(s.children[4]->value("translation")->floats, ElementsAre(0.5, 0.25));
}

TEST(ReadVrml1, IntegerBoolStringEnumBitmaskImage) {
  auto r = parse(R"(
    Separator {
      IndexedFaceSet { coordIndex [ 0, 1, 2, -1, 0x3, 2 1 -1 ] }
      PointLight { on FALSE }
      Info { string "a \"quoted\" \\ text" }
      AsciiText { string [ "one", "two" ] justification CENTER }
      Cone { parts ( SIDES | BOTTOM ) }
      Cylinder { parts TOP }
      Texture2 { image 2 1 3 0xFF0000 0x00ff00 }
      Switch { whichChild -1 }
    })");
  const auto& s = root(r);
  EXPECT_THAT(s.children[0]->value("coordIndex")->ints, ElementsAre(0, 1, 2, -1, 3, 2, 1, -1));
  EXPECT_THAT(s.children[1]->value("on")->ints, ElementsAre(0));
  EXPECT_THAT(s.children[2]->value("string")->strings, ElementsAre("a \"quoted\" \\ text"));
  EXPECT_THAT(s.children[3]->value("string")->strings, ElementsAre("one", "two"));
  EXPECT_THAT(s.children[3]->value("justification")->strings, ElementsAre("CENTER"));
  EXPECT_THAT(s.children[4]->value("parts")->strings, ElementsAre("SIDES", "BOTTOM"));
  EXPECT_THAT(s.children[5]->value("parts")->strings, ElementsAre("TOP"));
  EXPECT_THAT(s.children[6]->value("image")->ints, ElementsAre(2, 1, 3, 0xFF0000, 0x00FF00));
  EXPECT_THAT(s.children[7]->value("whichChild")->ints, ElementsAre(-1));
  EXPECT_EQ(r.log.count(LogLevel::kWarning), 0u);
}

TEST(ReadVrml1, DefaultsComeFromTheSchema) {
  auto r = parse("Cube { width 3 }");
  const auto& cube = root(r);
  EXPECT_FLOAT_EQ(scene::field_or_default(cube, "width")->floats[0], 3);
  EXPECT_FLOAT_EQ(scene::field_or_default(cube, "height")->floats[0], 2);
  EXPECT_EQ(cube.value("height"), nullptr);  // not given in the file
}

TEST(ReadVrml1, DefUseSharesOneNode) {
  auto r = parse(R"(
    Separator {
      DEF Red Material { diffuseColor 1 0 0 }
      Separator { USE Red Cube {} }
    })");
  const auto& s = root(r);
  EXPECT_EQ(s.children[0]->name, "Red");
  EXPECT_EQ(s.children[0].get(), s.children[1]->children[0].get());
}

TEST(ReadVrml1, UseTakesTheNewestDefinition) {
  auto r = parse(R"(
    Separator {
      DEF A Cube {} USE A
      DEF A Sphere {} USE A
    })");
  const auto& s = root(r);
  EXPECT_EQ(s.children[1]->type, "Cube");
  EXPECT_EQ(s.children[3]->type, "Sphere");
}

TEST(ReadVrml1, UseInsideItsOwnDefIsAnErrorNotACycle) {
  EXPECT_EQ(error_of("#VRML V1.0 ascii\nDEF Loop Separator { USE Loop }"),
            "t.wrl:2:26: USE of undefined node name 'Loop'");
}

TEST(ReadVrml1, UnknownNodeIsKeptVerbatimWithAWarningNamingItsLines) {
  auto r = parse("Separator {\n  BrowserHints {\n    headlight TRUE\n    foo [ 1, 2 ]\n  }\n}");
  const auto& hint = *root(r).children[0];
  EXPECT_TRUE(hint.is_raw);
  EXPECT_EQ(hint.raw_body, "\n    headlight TRUE\n    foo [ 1, 2 ]\n  ");
  ASSERT_EQ(r.log.count(LogLevel::kWarning), 1u);
  EXPECT_EQ(r.log.entries()[0].text, "t.wrl:3-6: unknown node type >BrowserHints< kept as it is");
}

TEST(ReadVrml1, UnknownFieldOfAKnownNodeIsKept) {
  auto r = parse("Material { diffuseColor 1 0 0 mirror 0.5 # comment\n fogImmune TRUE }");
  const auto& m = root(r);
  ASSERT_EQ(m.fields.size(), 3u);
  EXPECT_TRUE(m.fields[1].is_raw);
  EXPECT_EQ(m.fields[1].raw, "0.5");
  EXPECT_EQ(m.fields[2].raw, "TRUE");
  EXPECT_EQ(r.log.count(LogLevel::kWarning), 2u);
  EXPECT_THAT(r.log.entries()[0].text, HasSubstr("unknown field >mirror< of Material"));
}

// Inventor's marks after a value are no field names: `~` after a child
// node would join the field before it when written back.
TEST(ReadVrml1, MarksWhereAFieldNameIsExpectedAreAnError) {
  for (const std::string mark : {"~", "="})
    EXPECT_EQ(
        error_of("#Inventor V2.1 ascii\nSeparator { Cube { } " + mark + " D 1 }"),
        "t.wrl:2:22: expected a field name, a child node or '}' in Separator, got '" + mark + "'");
}

TEST(ReadVrml1, DeclarationWithAnUnknownFieldTypeIsAnError) {
  EXPECT_EQ(error_of("#VRML V1.0 ascii\nTorus { fields [ SFNode child ] }"),
            "t.wrl:2:18: expected a field type such as SFFloat or MFVec3f, or ']', got 'SFNode'");
}

TEST(ReadVrml1, ExtensionNodeFieldsAndIsA) {
  auto r = parse(R"(
    Torus {
      fields [ SFFloat bigRadius, MFVec3f pts ]
      isA [ "Group" ]
      bigRadius 2.5
      pts [ 0 0 0, 1 1 1 ]
      Cube {}
    })");
  const auto& t = root(r);
  EXPECT_FALSE(t.is_raw);
  ASSERT_EQ(t.declared.size(), 2u);
  EXPECT_EQ(scene::type_name(t.declared[1].type), "MFVec3f");
  EXPECT_THAT(t.is_a, ElementsAre("Group"));
  EXPECT_FLOAT_EQ(t.value("bigRadius")->floats[0], 2.5f);
  EXPECT_EQ(t.value("pts")->count(), 2u);
  ASSERT_EQ(t.children.size(), 1u);
  EXPECT_EQ(t.children[0]->type, "Cube");
}

TEST(ReadVrml1, CommentsAnywhere) {
  auto r = parse("# lead\nSeparator { # open\n Cube { width # mid\n 4 } # close\n } # end");
  EXPECT_FLOAT_EQ(root(r).children[0]->value("width")->floats[0], 4);
}

TEST(ReadVrml1, ErrorMessagesNameFileLineColumnAndToken) {
  EXPECT_EQ(error_of("#VRML V2.0 utf8\nShape {}"),
            "t.wrl:1:1: this is a VRML 2.0 (VRML97) file; lodforge reads VRML 1.0 (expected "
            "header '#VRML V1.0 ascii')");
  EXPECT_EQ(error_of("hello"), "t.wrl:1:1: expected header '#VRML V1.0 ascii', got 'hello'");
  EXPECT_EQ(error_of("#VRML V1.0 ascii\nCube { width abc }"),
            "t.wrl:2:14: expected a number for SFFloat field 'width', got 'abc'");
  EXPECT_EQ(error_of("#VRML V1.0 ascii\nCoordinate3 { point [ 1 2 3, 4 5 ] }"),
            "t.wrl:2:15: MFVec3f field 'point' needs a multiple of 3 numbers, got 5");
  EXPECT_EQ(error_of("#VRML V1.0 ascii\nSeparator {\n  Cube { }\n"),
            "t.wrl:4:1: expected a field name, a child node or '}' in Separator, got end of file");
  EXPECT_EQ(error_of("#VRML V1.0 ascii\nMaterialBinding { value PER_NOTHING }"),
            "t.wrl:2:25: expected one of DEFAULT, OVERALL, PER_PART, PER_PART_INDEXED, PER_FACE, "
            "PER_FACE_INDEXED, PER_VERTEX, PER_VERTEX_INDEXED for field 'value', got "
            "'PER_NOTHING'");
  EXPECT_EQ(error_of("#VRML V1.0 ascii\nCube { } USE Nothing"),
            "t.wrl:2:14: USE of undefined node name 'Nothing'");
  EXPECT_EQ(error_of("#VRML V1.0 ascii\nCube { Sphere { } }"),
            "t.wrl:2:8: Cube cannot have children; expected a field of Cube or '}', got 'Sphere'");
  EXPECT_EQ(error_of("#VRML V1.0 ascii\nSeparator { Cube { } 3 . }"),
            "t.wrl:2:22: expected a field name, a child node or '}' in Separator, got '3'");
  EXPECT_EQ(error_of("#VRML V1.0 ascii\nInfo { string \"open"),
            "t.wrl:2:15: unterminated string (missing closing '\"')");
  EXPECT_EQ(error_of("#VRML V1.0 ascii\nUnknown { { }"),
            "t.wrl:2:9: unterminated node: no '}' matches this '{'");
  EXPECT_EQ(error_of("#VRML V1.0 ascii\nIndexedFaceSet { coordIndex [ 0, 1, 99999999999 ] }"),
            "t.wrl:2:37: expected an integer or ']' for MFLong field 'coordIndex', got "
            "'99999999999'");
}

TEST(ReadVrml1, DeepNestingIsAClearErrorNotAStackOverflow) {
  std::string text = "#VRML V1.0 ascii\n";
  const int depth = 100000;
  for (int i = 0; i < depth; ++i) text += "Separator {\n";
  for (int i = 0; i < depth; ++i) text += "}\n";
  EXPECT_EQ(error_of(text), "t.wrl:258:1: nodes nested deeper than 256 levels");
}

TEST(ReadVrml1, NestingUpToTheLimitIsRead) {
  std::string text = "#VRML V1.0 ascii\n";
  for (int i = 0; i < 256; ++i) text += "Group {";
  for (int i = 0; i < 256; ++i) text += "}";
  auto r = read_vrml1(text);
  const scene::Node* n = r.scene.roots[0].get();
  int levels = 1;
  while (!n->children.empty()) {
    n = n->children[0].get();
    ++levels;
  }
  EXPECT_EQ(levels, 256);
}

TEST(ReadVrml1, InventorHeaderIsAccepted) {
  auto r = read_vrml1("#Inventor V2.1 ascii\nSeparator { Cube {} }");
  EXPECT_EQ(r.scene.header, "#Inventor V2.1 ascii");
}

}  // namespace
}  // namespace lodforge::vrml1
