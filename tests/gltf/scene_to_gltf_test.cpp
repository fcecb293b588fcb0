#include "lodforge/io/gltf/scene_to_gltf.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "lodforge/io/gltf/accessor_data.h"
#include "lodforge/io/vrml1/read_vrml1.h"

namespace lodforge::gltf {
namespace {

// A red square drawn up close, a triangle farther away, nothing beyond 20;
// and a blue triangle outside the LOD.
constexpr const char* kScene = R"(#VRML V1.0 ascii
Separator {
  PerspectiveCamera { heightAngle 0.5 }
  Material { diffuseColor 1 0 0 }
  DEF L LOD {
    range [10, 20]
    center 0.5 0.5 0
    Separator {
      Coordinate3 { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] }
      IndexedFaceSet { coordIndex [0, 1, 2, 3, -1] }
    }
    Separator {
      Coordinate3 { point [0 0 0, 1 0 0, 1 1 0] }
      IndexedFaceSet { coordIndex [0, 1, 2, -1] }
    }
    Info { string "empty" }
  }
  Material { diffuseColor 0 0 1 }
  Translation { translation 5 0 0 }
  Coordinate3 { point [0 0 0, 1 0 0, 0 1 0] }
  IndexedFaceSet { coordIndex [0, 1, 2, -1] }
})";

std::size_t triangles_of(const tinygltf::Model& m, int node) {
  std::size_t n = 0;
  for (const auto& p : m.meshes[std::size_t(m.nodes[std::size_t(node)].mesh)].primitives)
    n += m.accessors[std::size_t(p.indices)].count / 3;
  return n;
}

TEST(SceneToGltf, LodNodesBecomeMsftLodWithScreenCoverages) {
  Log log;
  const GltfScene g = scene_to_gltf(vrml1::read_vrml1(kScene).scene, {}, log);
  const tinygltf::Model& m = g.model;
  ASSERT_EQ(m.scenes.size(), 1u);
  // The plain triangle and the LOD's base node are shown; the level node is not.
  ASSERT_EQ(m.scenes[0].nodes.size(), 2u);
  EXPECT_EQ(m.nodes.size(), 3u);
  int base = -1;
  for (int n : m.scenes[0].nodes)
    if (m.nodes[std::size_t(n)].extensions.count("MSFT_lod")) base = n;
  ASSERT_GE(base, 0);
  EXPECT_EQ(m.nodes[std::size_t(base)].name, "L");
  EXPECT_EQ(triangles_of(m, base), 2u);
  const auto& ids = m.nodes[std::size_t(base)].extensions.at("MSFT_lod").Get("ids");
  ASSERT_EQ(ids.ArrayLen(), 1u);
  EXPECT_EQ(triangles_of(m, ids.Get(0).GetNumberAsInt()), 1u);
  EXPECT_EQ(m.extensionsUsed, std::vector<std::string>{"MSFT_lod"});
  // One coverage for the level, one where the empty child begins: the
  // square's bounding sphere (radius sqrt(2)/2 about its centre) over the
  // screen height seen at distance d with the camera's 0.5 rad.
  const auto& cov = m.nodes[std::size_t(base)].extras.Get("MSFT_screencoverage");
  ASSERT_EQ(cov.ArrayLen(), 2u);
  const double r = std::sqrt(2.0) / 2, t = std::tan(0.25);
  EXPECT_NEAR(cov.Get(0).GetNumberAsDouble(), r / (10 * t), 1e-6);
  EXPECT_NEAR(cov.Get(1).GetNumberAsDouble(), r / (20 * t), 1e-6);
  EXPECT_NEAR(
      m.nodes[std::size_t(base)].extras.Get("lodforge_lod").Get("camera_angle").GetNumberAsDouble(),
      0.5, 1e-6);
}

TEST(SceneToGltf, ShapesKeepTheirColoursAndWorldPlace) {
  Log log;
  const tinygltf::Model m = scene_to_gltf(vrml1::read_vrml1(kScene).scene, {}, log).model;
  bool saw_blue = false, saw_red = false;
  for (const auto& mesh : m.meshes)
    for (const auto& p : mesh.primitives) {
      ASSERT_TRUE(p.attributes.count("COLOR_0"));
      ASSERT_TRUE(p.attributes.count("NORMAL"));
      const AccessorValues c = read_accessor(m, p.attributes.at("COLOR_0"));
      const AccessorValues x = read_accessor(m, p.attributes.at("POSITION"));
      ASSERT_GT(c.count, 0u);
      const bool blue = c.values[2] > 0.5;
      saw_blue |= blue;
      saw_red |= !blue;
      // The blue triangle stands translated by 5 in x: world coordinates.
      double min_x = 1e30;
      for (std::size_t i = 0; i < x.count; ++i) min_x = std::min(min_x, x.values[3 * i]);
      EXPECT_EQ(min_x, blue ? 5.0 : 0.0);
      EXPECT_TRUE(m.materials[std::size_t(p.material)].doubleSided);
    }
  EXPECT_TRUE(saw_blue);
  EXPECT_TRUE(saw_red);
}

// Texture2 files beside the scene become images (file names as URIs); an
// inline image, a missing file or one that is no PNG or JPEG is left out
// with a warning, so the output stays valid.
TEST(SceneToGltf, TextureFilesBecomeImagesTheRestIsLeftOutWithWarnings) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("lodforge_scene_to_gltf_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "maps");
  std::ofstream(dir / "maps" / "wood grain.png") << "\x89PNG\r\n\x1a\n, not decoded";
  std::ofstream(dir / "maps" / "bark.tga") << "a Targa image";
  Log log;
  const tinygltf::Model m = scene_to_gltf(vrml1::read_vrml1(R"(#VRML V1.0 ascii
Separator {
  Coordinate3 { point [0 0 0, 1 0 0, 0 1 0] }
  Separator {
    Texture2 { filename "maps/wood grain.png" wrapS CLAMP }
    IndexedFaceSet { coordIndex [0, 1, 2, -1] }
  }
  Separator {
    Texture2 { image 1 1 3 0xff0000 }
    IndexedFaceSet { coordIndex [0, 2, 1, -1] }
  }
  Separator {
    Texture2 { filename "no_such_file.png" }
    IndexedFaceSet { coordIndex [1, 2, 0, -1] }
  }
  Separator {
    Texture2 { filename "maps/bark.tga" }
    IndexedFaceSet { coordIndex [2, 0, 1, -1] }
  }
})")
                                              .scene,
                                          {.base_dir = dir.string()}, log)
                                .model;
  std::filesystem::remove_all(dir);
  ASSERT_EQ(m.images.size(), 1u);
  EXPECT_EQ(m.images[0].uri, "maps/wood%20grain.png");
  ASSERT_EQ(m.samplers.size(), 1u);
  EXPECT_EQ(m.samplers[0].wrapS, TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE);
  EXPECT_EQ(m.samplers[0].wrapT, TINYGLTF_TEXTURE_WRAP_REPEAT);
  std::size_t textured = 0;
  for (const auto& mesh : m.meshes)
    for (const auto& p : mesh.primitives)
      textured +=
          p.attributes.count("TEXCOORD_0") &&
          m.materials[std::size_t(p.material)].pbrMetallicRoughness.baseColorTexture.index == 0;
  EXPECT_EQ(textured, 1u);
  std::string warnings;
  for (const auto& e : log.entries()) warnings += e.text + "\n";
  EXPECT_NE(warnings.find("inline"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("no_such_file.png"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("\"maps/bark.tga\" is no PNG or JPEG"), std::string::npos) << warnings;
}

}  // namespace
}  // namespace lodforge::gltf
