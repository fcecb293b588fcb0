// Relative file references follow a scene written to another folder.
#include "lodforge/scene/relocate_references.h"

#include <gtest/gtest.h>

#include "lodforge/io/vrml1/read_vrml1.h"

namespace lodforge::scene {
namespace {

const char* kScene = R"(#VRML V1.0 ascii
Separator {
  DEF T Texture2 { filename "textures/wood.png" }
  Separator { USE T Cube {} }
  Texture2 { filename "http://example.com/a.png" }
  Texture2 { filename "/abs/b.png" }
  Texture2 { filename "../shared/c.jpg" }
  WWWInline { name "parts/wheel.wrl" }
  Texture2 { }
}
)";

std::vector<std::string> names(const Scene& s) {
  std::vector<std::string> out;
  for (const auto& n : s.roots[0]->children)
    for (const char* f : {"filename", "name"})
      if (const FieldValue* v = n->value(f)) out.push_back(v->strings.at(0));
  return out;
}

TEST(RelocateReferences, RelativeNamesFollowTheOutputFolder) {
  Scene s = vrml1::read_vrml1(kScene).scene;
  RelocateResult r = relocate_references(s, "/data/scenes", "/data/out/lod");
  EXPECT_EQ(r.rewritten, 3u);  // the shared texture once, c.jpg, the inline
  EXPECT_EQ(names(s), (std::vector<std::string>{
                          "../../scenes/textures/wood.png", "http://example.com/a.png",
                          "/abs/b.png", "../../shared/c.jpg", "../../scenes/parts/wheel.wrl"}));
}

TEST(RelocateReferences, SameFolderChangesNothing) {
  Scene s = vrml1::read_vrml1(kScene).scene;
  EXPECT_EQ(relocate_references(s, "/data/scenes/", "/data/scenes/./").rewritten, 0u);
  EXPECT_EQ(names(s)[0], "textures/wood.png");
}

TEST(RelocateReferences, IntoASubfolderOfTheInput) {
  Scene s = vrml1::read_vrml1(kScene).scene;
  relocate_references(s, "/data/scenes", "/data/scenes/textures");
  EXPECT_EQ(names(s)[0], "wood.png");
}

}  // namespace
}  // namespace lodforge::scene
