// The X3D XML encoding: the reader gives the scene the classic reader gives
// for the same scene in the classic encoding; errors name the XML's line and
// column; the writer's output reads back to the same scene, over the corpus.
#include <gtest/gtest.h>

#include <algorithm>

#include "lodforge/core/error.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/vrml97/read_x3d_xml.h"
#include "lodforge/io/vrml97/write_vrml97.h"
#include "lodforge/io/vrml97/write_x3d_xml.h"
#include "vrml97/vrml97_corpus.h"

namespace lodforge::vrml97 {
namespace {

std::string error_of(std::string_view xml) {
  try {
    read_x3d_xml(xml, {.source_name = "t.x3d"});
  } catch (const ParseError& e) {
    return e.what();
  }
  return "";
}

constexpr std::string_view kXml = R"(<?xml version="1.0" encoding="UTF-8"?>
<X3D profile="Immersive" version="3.2">
<head><component name="Shaders" level="1"/><meta name="title" content="a &quot;test&quot;"/></head>
<Scene>
  <!-- a comment -->
  <ProtoDeclare name="Box2">
    <ProtoInterface>
      <field accessType="inputOutput" type="SFVec3f" name="size" value="2 2 2"/>
      <field accessType="initializeOnly" type="SFString" name="label"/>
      <field accessType="initializeOnly" type="SFNode" name="look"><Appearance/></field>
    </ProtoInterface>
    <ProtoBody>
      <Shape><IS><connect nodeField="appearance" protoField="look"/></IS>
        <Box><IS><connect nodeField="size" protoField="size"/></IS></Box></Shape>
    </ProtoBody>
  </ProtoDeclare>
  <Transform DEF="T" translation="1 2 3" rotation="0 1 0 1.5">
    <Shape>
      <Appearance><Material diffuseColor="1 0 0"/><ImageTexture url='"a.png" "b.png"' repeatS="false"/></Appearance>
      <IndexedFaceSet DEF="F" coordIndex="0 1 2 -1" solid="false" creaseAngle="0.5">
        <Coordinate point="0 0 0, 1 0 0, 0 1 0"/>
      </IndexedFaceSet>
    </Shape>
    <Shape><IndexedFaceSet USE="F"/></Shape>
    <ProtoInstance name="Box2" DEF="B"><fieldValue name="size" value="1 1 1"/><fieldValue name="label" value="x y"/></ProtoInstance>
  </Transform>
  <LOD range="10 20"><Group/><Group/><WorldInfo title="t" info='"i"'/></LOD>
  <Script DEF="S"><field accessType="inputOnly" type="SFTime" name="touched"/><![CDATA[ecmascript: function touched(v) {}]]></Script>
  <TimeSensor DEF="Clock" loop="true" cycleInterval="2"/>
  <ROUTE fromNode="Clock" fromField="fraction_changed" toNode="S" toField="touched"/>
</Scene>
</X3D>
)";

constexpr std::string_view kClassic = R"(#X3D V3.2 utf8
PROFILE Immersive
COMPONENT Shaders:1
META "title" "a \"test\""
PROTO Box2 [
  inputOutput SFVec3f size 2 2 2
  initializeOnly SFString label ""
  initializeOnly SFNode look Appearance { }
] { Shape { geometry Box { size IS size } appearance IS look } }
DEF T Transform { translation 1 2 3 rotation 0 1 0 1.5 children [
  Shape {
    appearance Appearance { material Material { diffuseColor 1 0 0 }
                            texture ImageTexture { url [ "a.png" "b.png" ] repeatS FALSE } }
    geometry DEF F IndexedFaceSet { coordIndex [ 0 1 2 -1 ] solid FALSE creaseAngle 0.5
                                    coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] } } }
  Shape { geometry USE F }
  DEF B Box2 { size 1 1 1 label "x y" } ] }
LOD { range [ 10 20 ] children [ Group { } Group { } WorldInfo { title "t" info "i" } ] }
DEF S Script { inputOnly SFTime touched url "ecmascript: function touched(v) {}" }
DEF Clock TimeSensor { loop TRUE cycleInterval 2 }
ROUTE Clock.fraction_changed TO S.touched
)";

// The node of `scene` at the path of root and field indices.
const scene::Node& root(const ReadResult& r, std::size_t i) {
  return *r.scene.roots.at(i);
}

TEST(X3dXml, ReadsTheSceneTheClassicEncodingGives) {
  const ReadResult xml = read_x3d_xml(kXml, {.source_name = "t.x3d"});
  const ReadResult classic = read_vrml97(kClassic, {.source_name = "t.x3dv"});
  EXPECT_EQ(xml.scene.header, "#X3D V3.2 utf8");
  // Node for node, the same types, names, typed values and sharing; raw
  // values and the PROTO text differ only in spacing, so compare those by
  // what the writer makes of them.
  ASSERT_EQ(xml.scene.roots.size(), classic.scene.roots.size());
  for (std::size_t i = 0; i < xml.scene.roots.size(); ++i)
    EXPECT_EQ(root(xml, i).type, root(classic, i).type) << i;
  const scene::Node& t = root(xml, 4);
  EXPECT_EQ(t.name, "T");
  EXPECT_EQ(t.value("translation")->floats, (std::vector<float>{1, 2, 3}));
  const auto& children = t.value("children")->nodes;
  ASSERT_EQ(children.size(), 3u);
  // The USE shares the node, as in the classic encoding.
  EXPECT_EQ(children[0]->value("geometry")->nodes[0], children[1]->value("geometry")->nodes[0]);
  const scene::Node& ifs = *children[0]->value("geometry")->nodes[0];
  EXPECT_EQ(ifs.value("coordIndex")->ints, (std::vector<std::int32_t>{0, 1, 2, -1}));
  EXPECT_EQ(ifs.value("solid")->ints, (std::vector<std::int32_t>{0}));
  EXPECT_EQ(ifs.value("coord")->nodes[0]->value("point")->floats.size(), 9u);
  EXPECT_EQ(children[2]->type, "Box2");
  EXPECT_EQ(write_x3d_xml(xml.scene), write_x3d_xml(classic.scene));
}

TEST(X3dXml, DefaultsOfFieldsAndContainers) {
  const ReadResult r = read_x3d_xml(R"(<X3D version="4.0"><Scene>
<Shape><Appearance><Material/></Appearance><Sphere radius="2"/></Shape>
<Switch whichChoice="1"><Transform/><Group/></Switch>
<Shape><Appearance><ImageTexture containerField="texture"/></Appearance>
  <ElevationGrid xDimension="2" zDimension="2" height="0 1 2 3"/></Shape></Scene></X3D>)");
  EXPECT_EQ(r.scene.header, "#X3D V4.0 utf8");
  const scene::Node& shape = root(r, 0);
  EXPECT_EQ(shape.value("appearance")->nodes.at(0)->type, "Appearance");
  EXPECT_EQ(shape.value("geometry")->nodes.at(0)->value("radius")->floats.at(0), 2.f);
  EXPECT_EQ(root(r, 1).value("children")->nodes.size(), 2u);
  EXPECT_EQ(root(r, 2).value("geometry")->nodes.at(0)->value("height")->floats.size(), 4u);
}

TEST(X3dXml, ErrorsNameTheLineAndColumnOfTheXml) {
  // Malformed XML (pugixml's verdict, at the end tag that does not match).
  EXPECT_EQ(error_of("<X3D><Scene><Group></Scene></X3D>").substr(0, 11), "t.x3d:1:22:");
  // Not an X3D document.
  EXPECT_EQ(error_of("<svg/>"), "t.x3d:1:2: expected the root element <X3D>, got <svg>");
  // A bad number in a typed field: the attribute's position.
  const std::string bad =
      error_of("<X3D><Scene>\n<Transform\n  translation='1 x 3'/></Scene></X3D>");
  EXPECT_EQ(bad.substr(0, 10), "t.x3d:3:3:") << bad;
  EXPECT_NE(bad.find("translation"), std::string::npos) << bad;
  // A USE of a name never DEFined, found by the classic reader, reported at the element.
  const std::string use =
      error_of("<X3D><Scene>\n<Group>\n <Shape USE='Nope'/></Group></Scene></X3D>");
  EXPECT_EQ(use.substr(0, 10), "t.x3d:3:3:") << use;
  EXPECT_NE(use.find("Nope"), std::string::npos) << use;
  // Lines of a script's text do not shift the positions after it.
  const std::string after_script = error_of(
      "<X3D><Scene>\n<Script><![CDATA[ecmascript:\n\n\nfunction f() {}\n]]></Script>\n"
      "<Group>\n <Shape USE='Nope'/></Group></Scene></X3D>");
  EXPECT_EQ(after_script.substr(0, 10), "t.x3d:8:3:") << after_script;
  // An element where a node is expected that is none.
  EXPECT_EQ(error_of("<X3D><Scene><connect/></Scene></X3D>"),
            "t.x3d:1:14: <connect> is not allowed here");
  // A component level that is not a whole number (found by fuzzing: the
  // writer finds the level after the last colon, so it must hold none).
  EXPECT_EQ(error_of("<X3D><head><component name='Shaders' level='1:2'/></head></X3D>"),
            "t.x3d:1:38: expected a whole number for level of <component>, got '1:2'");
  // A <field> without its type.
  EXPECT_NE(
      error_of(
          "<X3D><Scene><Script><field name='a' accessType='inputOnly'/></Script></Scene></X3D>")
          .find("<field> needs the attribute type"),
      std::string::npos);
}

TEST(X3dXml, DeepNestingIsAnErrorNotACrash) {
  std::string xml = "<X3D><Scene>";
  for (int i = 0; i < 5000; ++i) xml += "<Group>";
  for (int i = 0; i < 5000; ++i) xml += "</Group>";
  xml += "</Scene></X3D>";
  EXPECT_NE(error_of(xml).find("nested deeper than"), std::string::npos);
}

// Found by fuzzing: a value not of the type the tables give its field name
// (here an undeclared prototype's) reads as a string and writes back the
// same; a node type that is no XML name is an error, not a broken document.
TEST(X3dXml, ValuesAndNamesTheTablesDoNotFit) {
  const ReadResult r = read_x3d_xml(
      R"(<X3D><Scene><ProtoInstance name="Box1"><fieldValue name="size" value="1 q 1"/>
         </ProtoInstance></Scene></X3D>)");
  const std::string xml = write_x3d_xml(r.scene);
  EXPECT_NE(xml.find(R"(size="1 q 1")"), std::string::npos) << xml;
  EXPECT_EQ(write_x3d_xml(read_x3d_xml(xml).scene), xml);
  // A number beyond float's range is read as infinity (as by the classic
  // reader) and written back as inf.
  const std::string huge = write_x3d_xml(
      read_x3d_xml(R"(<X3D><Scene><Coordinate point="0 1 1e99"/></Scene></X3D>)").scene);
  EXPECT_NE(huge.find(R"(point="0 1 inf")"), std::string::npos) << huge;
  EXPECT_EQ(write_x3d_xml(read_x3d_xml(huge).scene), huge);
  // Text inside a node that holds no code is not part of the scene (it was
  // taken as a url, which a prototype instance then wrote back as a field).
  const std::string text =
      write_x3d_xml(read_x3d_xml(R"(<X3D><Scene><ProtoInstance name="P"> 1"/></ProtoInstance>
                      <Group>words</Group></Scene></X3D>)")
                        .scene);
  EXPECT_EQ(text.find("url"), std::string::npos) << text;
  EXPECT_EQ(write_x3d_xml(read_x3d_xml(text).scene), text);
  // An attribute named as a keyword of the classic encoding is no field name
  // (EXPORT in a node's body would read as a statement).
  EXPECT_NE(error_of(R"(<X3D><Scene><TimeSenso EXPORT="x"/></Scene></X3D>)")
                .find("expected a name for attribute name of <TimeSenso>, got 'EXPORT'"),
            std::string::npos);
  // A string of a field no table types stays one string: quoted when,
  // unquoted, it would be read as another (spaces trimmed, numbers).
  for (const char* value : {R"('"&#9;.png"')", R"('"12"')", R"('"two words"')"}) {
    const std::string once = write_x3d_xml(
        read_x3d_xml(std::string("<X3D><Scene><Foo rl=") + value + "/></Scene></X3D>").scene);
    EXPECT_EQ(write_x3d_xml(read_x3d_xml(once).scene), once) << value;
  }
  const ReadResult amp = read_vrml97("#X3D V3.2 utf8\nBox& { }\n");
  EXPECT_THROW(write_x3d_xml(amp.scene), DataError);
}

TEST(X3dXml, WriterNeedsAnX3dHeader) {
  const ReadResult r = read_vrml97("#VRML V2.0 utf8\nGroup { }\n");
  EXPECT_THROW(write_x3d_xml(r.scene), DataError);
}

// Every corpus scene, classic or XML: read, written as XML, read again:
// the same nodes and the same document when written again.
std::size_t scene_roots(const scene::Scene& s) {
  return std::size_t(std::count_if(s.roots.begin(), s.roots.end(), [](const auto& n) {
    return !n->statement || (n->type != "PROFILE" && n->type != "COMPONENT" && n->type != "META" &&
                             n->type != "UNIT");
  }));
}

class X3dXmlRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(X3dXmlRoundTrip, WrittenAsXmlReadsBackToTheSameScene) {
  ReadResult first =
      is_x3d_xml_path(GetParam()) ? read_x3d_xml_file(GetParam()) : read_vrml97_file(GetParam());
  if (!is_x3d_header(first.scene.header)) first.scene.header = "#X3D V3.0 utf8";
  const std::string xml = write_x3d_xml(first.scene);
  const ReadResult second = read_x3d_xml(xml, {.source_name = "written.x3d"});
  EXPECT_EQ(xml, write_x3d_xml(second.scene)) << GetParam();
  // Typed values survive exactly: the classic text of both is the same but
  // for the raw values' spacing, which the XML writer normalises.
  EXPECT_EQ(write_vrml97(read_x3d_xml(write_x3d_xml(second.scene)).scene),
            write_vrml97(second.scene));
  EXPECT_EQ(scene_roots(first.scene), scene_roots(second.scene)) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Corpus, X3dXmlRoundTrip,
                         ::testing::ValuesIn(testing::vrml97_corpus_files(true)),
                         [](const auto& info) { return testing::corpus_test_name(info.param); });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(X3dXmlRoundTrip);

}  // namespace
}  // namespace lodforge::vrml97
