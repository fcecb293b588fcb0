// The X3D XML writer: escaping, containerField, sharing, VRML97 scenes, and
// what it refuses.
#include "lodforge/io/x3dxml/write_x3d_xml.h"

#include <gtest/gtest.h>

#include "lodforge/core/error.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/x3dxml/read_x3d_xml.h"

namespace lodforge::x3dxml {
namespace {

TEST(WriteX3dXml, EscapesTextAndReadsBackTheSameScene) {
  const auto r = vrml97::read_vrml97(R"(#X3D V3.3 utf8
PROFILE Immersive
META "author" "A & B <c>"
DEF V Viewpoint { description "say \"hi\" & <go>" position 0 0 5 }
Shape { geometry Text { string [ "a \"quoted\" one" "two & three" ] } }
DEF S Script { initializeOnly SFString s "it's" url "ecmascript:
function f() { return 1 < 2; }" }
)");
  const std::string xml = write_x3d_xml(r.scene);
  EXPECT_NE(xml.find("<X3D profile=\"Immersive\" version=\"3.3\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<meta name=\"author\" content=\"A &amp; B &lt;c&gt;\" />"), std::string::npos)
      << xml;
  EXPECT_NE(xml.find("description='say \"hi\" &amp; &lt;go&gt;'"), std::string::npos) << xml;
  EXPECT_NE(xml.find("string='\"a \\\"quoted\\\" one\" \"two &amp; three\"'"), std::string::npos)
      << xml;
  EXPECT_NE(xml.find("&#10;function f() { return 1 &lt; 2; }"), std::string::npos) << xml;
  const auto back = read_x3d_xml(xml);
  ASSERT_EQ(back.scene.roots.size(), r.scene.roots.size());
  ASSERT_NE(back.scene.roots[2]->find("description"), nullptr);
  EXPECT_EQ(back.scene.roots[2]->find("description")->value.strings,
            (std::vector<std::string>{"say \"hi\" & <go>"}));
  ASSERT_EQ(back.scene.roots[4]->fields.size(), 2u);
  EXPECT_EQ(back.scene.roots[4]->find("url")->raw, r.scene.roots[4]->find("url")->raw);
  EXPECT_EQ(write_x3d_xml(back.scene), xml);
}

TEST(WriteX3dXml, NamesFieldsThatAreNotTheDefaultAndSharesNodes) {
  auto r = vrml97::read_vrml97(R"(#VRML V2.0 utf8
Collision { proxy DEF B Shape { geometry Box {} } children [ USE B ] }
LOD { level [ Shape { geometry Sphere {} } Group {} ] range [ 10 ] }
)");
  // A node shared without a name gets one.
  r.scene.roots[0]->fields[1].value.nodes[0]->name.clear();
  const std::string xml = write_x3d_xml(r.scene);
  EXPECT_NE(xml.find("<X3D version=\"3.0\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<Shape DEF=\"lf_1\" containerField=\"proxy\">"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<Shape USE=\"lf_1\" />"), std::string::npos) << xml;
  // VRML97's LOD level is X3D's children, the default field.
  EXPECT_NE(xml.find("<LOD\n\t\trange=\"10\">\n\t\t<Shape>"), std::string::npos) << xml;
  const auto back = read_x3d_xml(xml);
  const auto* lod_children = back.scene.roots[1]->value("children");
  ASSERT_NE(lod_children, nullptr);
  EXPECT_EQ(lod_children->nodes.size(), 2u);
}

TEST(WriteX3dXml, RefusesPrototypesAndOtherEncodings) {
  const auto r = vrml97::read_vrml97("#X3D V3.0 utf8\nPROTO P [] { Group {} }\nP {}\n");
  try {
    write_x3d_xml(r.scene);
    FAIL() << "a PROTO was written";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("PROTO cannot be written"), std::string::npos);
  }
  scene::Scene vrml1;
  EXPECT_THROW(write_x3d_xml(vrml1), DataError);
}

}  // namespace
}  // namespace lodforge::x3dxml
