// The X3D XML reader: the scene the classic reader gives for the same scene,
// statements, errors with the XML line and column, and the read -> write ->
// read round trip over the corpus.
#include "lodforge/io/x3dxml/read_x3d_xml.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "lodforge/core/error.h"
#include "lodforge/io/x3dxml/write_x3d_xml.h"

namespace lodforge::x3dxml {
namespace {

std::string error_of(std::string_view text) {
  try {
    read_x3d_xml(text, {.source_name = "t.x3d"});
  } catch (const ParseError& e) {
    return e.what();
  }
  return "";
}

TEST(ReadX3dXml, GivesTheSceneTheClassicEncodingGives) {
  const auto xml = read_x3d_xml(R"(<?xml version="1.0" encoding="UTF-8"?>
<X3D profile="Interchange" version="3.2">
<head><component name="Shaders" level="1"/><meta name="title" content="a &quot;test&quot;"/>
  <unit category="length" name="cm" conversionFactor="0.01"/></head>
<Scene>
  <Transform DEF="T" translation="1 2 3">
    <Shape DEF="S">
      <Appearance><Material diffuseColor="1 0 0"/>
        <ImageTexture url='"a.png" "b.png"' repeatS="false"/></Appearance>
      <IndexedFaceSet coordIndex="0 1 2 -1" solid="false">
        <Coordinate DEF="C" point="0 0 0, 1 0 0, 0 1 0"/>
      </IndexedFaceSet>
    </Shape>
    <Transform><Shape USE="S"/></Transform>
  </Transform>
  <Collision><Shape containerField="proxy"><Box size="1 2 3"/></Shape></Collision>
  <Viewpoint description="front" position="0 0 10"/>
  <NavigationInfo type='"EXAMINE" "ANY"' avatarSize="0.25 1.6 0.75"/>
</Scene>
</X3D>
)");
  const auto classic = vrml97::read_vrml97(R"(#X3D V3.2 utf8
PROFILE Interchange
COMPONENT Shaders:1
META "title" "a \"test\""
UNIT length cm 0.01
DEF T Transform { translation 1 2 3 children [
  DEF S Shape { appearance Appearance { material Material { diffuseColor 1 0 0 }
      texture ImageTexture { url [ "a.png" "b.png" ] repeatS FALSE } }
    geometry IndexedFaceSet { coordIndex [ 0 1 2 -1 ] solid FALSE
      coord DEF C Coordinate { point [0 0 0, 1 0 0, 0 1 0] } } }
  Transform { children USE S } ] }
Collision { proxy Shape { geometry Box { size 1 2 3 } } }
Viewpoint { description "front" position 0 0 10 }
NavigationInfo { type [ "EXAMINE" "ANY" ] avatarSize [ 0.25 1.6 0.75 ] }
)");
  EXPECT_TRUE(scene::equal(xml.scene, classic.scene))
      << x3d_xml_to_classic(write_x3d_xml(xml.scene), "w");
  EXPECT_EQ(xml.scene.header, "#X3D V3.2 utf8");
  // Lines are the XML file's.
  EXPECT_EQ(xml.scene.roots[4]->first_line, 6);
}

TEST(ReadX3dXml, PrototypesScriptsAndRoutesAreStatements) {
  const auto r = read_x3d_xml(R"(<X3D version="3.3"><Scene>
  <ProtoDeclare name="Label">
    <ProtoInterface><field accessType="initializeOnly" type="MFString" name="text" value='"x"'/>
    </ProtoInterface>
    <ProtoBody><Shape><Text><IS><connect nodeField="string" protoField="text"/></IS></Text></Shape>
    </ProtoBody>
  </ProtoDeclare>
  <ProtoInstance name="Label" DEF="L"><fieldValue name="text" value='"a" "b"'/></ProtoInstance>
  <TimeSensor DEF="TS" loop="true"/>
  <Script DEF="S"><field accessType="inputOnly" type="SFTime" name="t"/>
    <field accessType="initializeOnly" type="SFNode" name="n"><TimeSensor USE="TS"/></field>
<![CDATA[ecmascript:
function t(v) { if (v < 1 && v > 0) {} }
]]></Script>
  <ROUTE fromNode="TS" fromField="time" toNode="S" toField="t"/>
  <EXPORT localDEF="TS" AS="Clock"/>
</Scene></X3D>)");
  ASSERT_EQ(r.scene.roots.size(), 6u);
  EXPECT_EQ(r.scene.roots[0]->type, "PROTO");
  EXPECT_EQ(r.scene.roots[0]->raw_body,
            "Label [\ninitializeOnly MFString text \"x\" ] {\nShape {\ngeometry\nText {\nstring IS "
            "text } } }");
  const auto& label = *r.scene.roots[1];
  EXPECT_EQ(label.type, "Label");
  EXPECT_EQ(label.name, "L");
  ASSERT_EQ(label.fields.size(), 1u);
  EXPECT_EQ(label.fields[0].raw, "[ \"a\" \"b\" ]");
  const auto& script = *r.scene.roots[3];
  ASSERT_EQ(script.fields.size(), 3u);
  EXPECT_EQ(script.fields[0].name, "inputOnly SFTime t");
  EXPECT_EQ(script.fields[1].value.nodes.at(0), r.scene.roots[2]);
  EXPECT_NE(script.fields[2].raw.find("v < 1 && v > 0"), std::string::npos);
  EXPECT_EQ(r.scene.roots[4]->raw_body, "TS.time TO S.t");
  EXPECT_EQ(r.scene.roots[5]->raw_body, "TS AS Clock");
}

TEST(ReadX3dXml, ErrorsNameTheXmlLineAndColumn) {
  EXPECT_EQ(error_of("<X3D>\n<Scene>\n  <Transform>\n</Scene></X3D>"),
            "t.x3d:4:3: malformed XML: Start-end tags mismatch");
  EXPECT_EQ(error_of("<X3D><Scene>\n\n  <Transform translation='1 x 3'/></Scene></X3D>"),
            "t.x3d:3:3: expected a number for SFVec3f field 'translation', got '\"1 x 3\"'");
  EXPECT_EQ(error_of("<X3D><Scene>\n <Shape USE='nothing'/></Scene></X3D>"),
            "t.x3d:2:2: USE of undefined node name 'nothing'");
  EXPECT_EQ(error_of("<?xml version='1.0'?>\n<html/>"),
            "t.x3d:2:1: expected an <X3D> document, got <html>");
  EXPECT_EQ(error_of("<X3D><Scene><ROUTE fromNode='A'/></Scene></X3D>"),
            "t.x3d:1:13: <ROUTE> without the attribute fromField");
}

std::vector<std::string> corpus_files() {
  std::vector<std::string> out;
  const std::string root = std::string(LODFORGE_SHARED_DATA) + "/x3d";
  std::error_code ec;
  if (!std::filesystem::is_directory(root, ec)) return out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(root))
    if (e.is_regular_file() && e.path().extension() == ".x3d") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

std::string test_name(const std::string& path) {
  std::string s = path.substr(std::string(LODFORGE_SHARED_DATA).size() + 1);
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

class RoundTrip : public ::testing::TestWithParam<std::string> {};

// read -> write -> read: the same scene (nodes, fields, values, sharing), and
// the written text is a fixed point. A scene with a PROTO is refused with a
// message naming it.
TEST_P(RoundTrip, WriteThenReadGivesTheSameScene) {
  const vrml97::ReadResult first = read_x3d_xml_file(GetParam());
  ASSERT_FALSE(first.scene.roots.empty()) << GetParam();
  std::string text;
  try {
    text = write_x3d_xml(first.scene);
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("PROTO"), std::string::npos) << e.what();
    return;
  }
  const vrml97::ReadResult second = read_x3d_xml(text, {.source_name = "written"});
  EXPECT_TRUE(scene::equal(first.scene, second.scene)) << GetParam();
  EXPECT_EQ(text, write_x3d_xml(second.scene));
}

INSTANTIATE_TEST_SUITE_P(Corpus, RoundTrip, ::testing::ValuesIn(corpus_files()),
                         [](const auto& info) { return test_name(info.param); });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(RoundTrip);

TEST(RoundTripCorpus, CorpusIsPresent) {
  EXPECT_GE(corpus_files().size(), 15u) << "expected the corpus at " << LODFORGE_SHARED_DATA;
}

}  // namespace
}  // namespace lodforge::x3dxml
