// VRML 1.0 / Inventor scenes converted to VRML97 and X3D classic: LOD nodes
// with their ranges and world-space centres, colours, textures, the shapes
// without geometry named in a warning, and output our reader reads back.
#include "lodforge/io/vrml97/vrml1_to_vrml97.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/vrml97/write_vrml97.h"

namespace lodforge::vrml97 {
namespace {

using scene::Node;
using ::testing::HasSubstr;

scene::Scene convert(const std::string& vrml1, Log& log, bool x3d = false) {
  const scene::Scene out = vrml1_to_vrml97(vrml1::read_vrml1(vrml1).scene, {.x3d = x3d}, log);
  // What is written is read back the same.
  return read_vrml97(write_vrml97(out)).scene;
}

const scene::FieldValue& field(const Node& n, const char* name) {
  const scene::FieldValue* v = n.value(name);
  EXPECT_NE(v, nullptr) << n.type << "." << name;
  static const scene::FieldValue none;
  return v ? *v : none;
}

const Node& geometry(const Node& shape) {
  return *field(shape, "geometry").nodes.at(0);
}
const Node& material(const Node& shape) {
  return *field(*field(shape, "appearance").nodes.at(0), "material").nodes.at(0);
}

constexpr const char* kLodScene = R"(#VRML V1.0 ascii
Separator {
  Translation { translation 10 0 0 }
  DEF far LOD {
    range [ 5, 20 ]
    center 1 0 0
    Separator { Material { diffuseColor 1 0 0 } Cube { width 2 height 2 depth 2 } }
    Separator { Coordinate3 { point [ 0 0 0, 1 0 0, 0 1 0, 1 1 0 ] }
                IndexedFaceSet { coordIndex [ 0, 1, 3, 2, -1 ] } }
    Separator { }
  }
}
)";

TEST(Vrml1ToVrml97, LodKeepsRangesNameAndChildrenWithItsCentreInWorldSpace) {
  Log log;
  const scene::Scene s = convert(kLodScene, log);
  EXPECT_EQ(s.header, "#VRML V2.0 utf8");
  ASSERT_EQ(s.roots.size(), 1u);
  const Node& lod = *s.roots[0];
  EXPECT_EQ(lod.type, "LOD");
  EXPECT_EQ(lod.name, "far");
  EXPECT_EQ(field(lod, "range").floats, (std::vector<float>{5, 20}));
  EXPECT_EQ(field(lod, "center").floats, (std::vector<float>{11, 0, 0}));
  const auto& levels = field(lod, "level").nodes;
  ASSERT_EQ(levels.size(), 3u);
  // Child 0: the cube, tessellated in world space, red.
  const Node& cube = *field(*levels[0], "children").nodes.at(0);
  const Node& faces = geometry(cube);
  EXPECT_EQ(faces.type, "IndexedFaceSet");
  EXPECT_EQ(field(faces, "coordIndex").ints.size(), 12u * 4);
  for (std::size_t i = 0; i < field(*field(faces, "coord").nodes[0], "point").floats.size(); i += 3)
    EXPECT_NEAR(field(*field(faces, "coord").nodes[0], "point").floats[i], 10, 1.0001);
  EXPECT_EQ(field(material(cube), "diffuseColor").floats, (std::vector<float>{1, 0, 0}));
  // Child 1: the quad as two triangles; child 2 empty.
  EXPECT_EQ(field(geometry(*field(*levels[1], "children").nodes.at(0)), "coordIndex").ints.size(),
            8u);
  EXPECT_EQ(levels[2]->value("children"), nullptr);
}

TEST(Vrml1ToVrml97, X3dClassicHasItsHeaderProfileAndLodChildren) {
  Log log;
  const scene::Scene s = convert(kLodScene, log, true);
  EXPECT_EQ(s.header, "#X3D V3.0 utf8");
  ASSERT_EQ(s.roots.size(), 2u);
  EXPECT_EQ(s.roots[0]->type, "PROFILE");
  EXPECT_EQ(field(*s.roots[1], "children").nodes.size(), 3u);
}

TEST(Vrml1ToVrml97, MaterialsPerFaceBecomeColoursAndOneMaterialAMaterial) {
  Log log;
  const scene::Scene s = convert(R"(#VRML V1.0 ascii
Separator {
  Coordinate3 { point [ 0 0 0, 1 0 0, 0 1 0, 1 1 0 ] }
  Material { diffuseColor [ 1 0 0, 0 0 1 ] transparency [ 0.5 ] }
  MaterialBinding { value PER_FACE }
  IndexedFaceSet { coordIndex [ 0, 1, 2, -1, 1, 3, 2, -1 ] }
  MaterialBinding { value OVERALL }
  IndexedLineSet { coordIndex [ 0, 1, 3 ] }
}
)",
                                 log);
  ASSERT_EQ(s.roots.size(), 2u);
  const Node& faces = geometry(*s.roots[0]);
  const auto& colours = field(*field(faces, "color").nodes.at(0), "color").floats;
  ASSERT_EQ(colours.size(), 6u * 3);  // split per face: 3 corners each
  EXPECT_EQ(std::vector<float>(colours.begin(), colours.begin() + 3),
            (std::vector<float>{1, 0, 0}));
  EXPECT_EQ(std::vector<float>(colours.end() - 3, colours.end()), (std::vector<float>{0, 0, 1}));
  EXPECT_EQ(field(material(*s.roots[0]), "transparency").floats, (std::vector<float>{0.5f}));
  // Lines are unlit in VRML97: the colour is emissive.
  EXPECT_EQ(geometry(*s.roots[1]).type, "IndexedLineSet");
  EXPECT_EQ(field(material(*s.roots[1]), "emissiveColor").floats, (std::vector<float>{1, 0, 0}));
}

TEST(Vrml1ToVrml97, TexturesKeepTheirFileOrInlineImage) {
  Log log;
  const scene::Scene s = convert(R"(#VRML V1.0 ascii
Separator {
  Separator {
    Texture2 { filename "wood.png" wrapS CLAMP }
    Cube { }
  }
  Texture2 { image 2 1 1 0x00 0xff }
  Sphere { }
}
)",
                                 log);
  ASSERT_EQ(s.roots.size(), 2u);
  auto texture = [](const Node& shape) -> const Node& {
    return *field(*field(shape, "appearance").nodes.at(0), "texture").nodes.at(0);
  };
  EXPECT_EQ(texture(*s.roots[0]).type, "ImageTexture");
  // (The reader keeps ImageTexture's fields as text.)
  const std::string written = write_vrml97(s);
  EXPECT_THAT(written, HasSubstr("url \"wood.png\""));
  EXPECT_THAT(written, HasSubstr("repeatS FALSE"));
  EXPECT_NE(geometry(*s.roots[0]).value("texCoord"), nullptr);
  EXPECT_EQ(texture(*s.roots[1]).type, "PixelTexture");
}

TEST(Vrml1ToVrml97, WhatIsNotCarriedIsNamedInAWarning) {
  Log log;
  const scene::Scene s = convert(R"(#VRML V1.0 ascii
Separator {
  PerspectiveCamera { }
  AsciiText { string "hello" }
  Cube { }
}
)",
                                 log);
  EXPECT_EQ(s.roots.size(), 1u);
  std::string text;
  for (const auto& d : log.entries()) text += d.text + "\n";
  EXPECT_THAT(text, HasSubstr("1 AsciiText"));
  EXPECT_THAT(text, HasSubstr("1 PerspectiveCamera"));
}

}  // namespace
}  // namespace lodforge::vrml97
