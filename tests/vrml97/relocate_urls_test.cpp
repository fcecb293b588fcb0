// Relative url fields of VRML97 / X3D scenes follow a scene written to
// another folder (scene::relocate_references on what the VRML97 reader makes).
#include <gtest/gtest.h>

#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/scene/relocate_references.h"

namespace lodforge::scene {
namespace {

// VRML97 / X3D: every value of a url field, in nodes held by fields (a
// Shape's appearance), a '#name' after the path kept; URLs, names within the
// file and program code left alone.
TEST(RelocateReferences, Vrml97UrlFields) {
  Scene s = vrml97::read_vrml97(R"(#VRML V2.0 utf8
Transform { children [
  Shape { appearance Appearance { texture ImageTexture { url [ "t/a.png" "https://x.org/a.png" ] } } }
  Anchor { url [ "#Inside" "next.wrl#View" ] }
] }
Background { frontUrl "sky.jpg" }
Script { url [ "javascript: function f() {}" "
  function g() {}" ] }
)")
                .scene;
  EXPECT_EQ(relocate_references(s, "/data/in", "/data/out").rewritten, 3u);
  const Node& group = *s.roots[0];
  const Node& shape = *group.value("children")->nodes[0];
  const Node& texture = *shape.value("appearance")->nodes[0]->value("texture")->nodes[0];
  EXPECT_EQ(texture.value("url")->strings,
            (std::vector<std::string>{"../in/t/a.png", "https://x.org/a.png"}));
  EXPECT_EQ(group.value("children")->nodes[1]->value("url")->strings,
            (std::vector<std::string>{"#Inside", "../in/next.wrl#View"}));
  EXPECT_EQ(s.roots[1]->value("frontUrl")->strings, (std::vector<std::string>{"../in/sky.jpg"}));
  EXPECT_EQ(s.roots[2]->value("url")->strings.at(0), "javascript: function f() {}");
  EXPECT_EQ(s.roots[2]->value("url")->strings.at(1), "\n  function g() {}");
}

}  // namespace
}  // namespace lodforge::scene
