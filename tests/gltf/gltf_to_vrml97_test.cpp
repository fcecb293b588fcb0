// A glTF model as a VRML97 scene: the same triangles in the same places
// (Transforms from TRS and matrices, meshes shared by DEF/USE), materials and
// textures, and what VRML97 cannot hold named in a warning.
#include "lodforge/io/gltf/gltf_to_vrml97.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "gltf/gltf_corpus.h"
#include "gltf_builder.h"
#include "lodforge/core/error.h"
#include "lodforge/io/gltf/scene_mesh.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/vrml97/write_vrml97.h"
#include "lodforge/lod/flatten_vrml97.h"

namespace lodforge::gltf {
namespace {

// Mesh 0 (one triangle, double-sided, half-transparent, with an embedded
// PNG clamped in s) is used by node 0 (rotated a quarter turn about y,
// scaled) and node 1 (a matrix that mirrors x and moves by 5 in z); node 2,
// node 1's child, holds mesh 1 (a line).
tinygltf::Model two_nodes_one_mesh() {
  tinygltf::Model m;
  const int p = testing::add_floats(m, {0, 0, 0, 1, 0, 0, 0, 1, 0}, TINYGLTF_TYPE_VEC3);
  const int uv = testing::add_floats(m, {0, 0, 1, 0, 0, 0.25f}, TINYGLTF_TYPE_VEC2);
  tinygltf::Primitive tri;
  tri.attributes = {{"POSITION", p}, {"TEXCOORD_0", uv}};
  tri.material = 0;
  tri.mode = TINYGLTF_MODE_TRIANGLES;
  m.meshes.emplace_back().primitives.push_back(tri);
  tinygltf::Primitive line;
  line.attributes = {{"POSITION", p}};
  line.indices = testing::add_indices(m, {0, 1});
  line.mode = TINYGLTF_MODE_LINE;
  line.material = 0;
  m.meshes.emplace_back().primitives.push_back(line);

  tinygltf::Material mat;
  mat.pbrMetallicRoughness.baseColorFactor = {0.5, 0.25, 1, 0.5};
  mat.alphaMode = "BLEND";
  mat.doubleSided = true;
  mat.pbrMetallicRoughness.baseColorTexture.index = 0;
  m.materials.push_back(mat);
  tinygltf::Sampler sampler;
  sampler.wrapS = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  m.samplers.push_back(sampler);
  tinygltf::Texture texture;
  texture.source = 0;
  texture.sampler = 0;
  m.textures.push_back(texture);
  tinygltf::Image image;
  image.image = {0x89, 'P', 'N', 'G', 1, 2, 3};
  image.as_is = true;
  m.images.push_back(image);

  m.nodes.resize(3);
  m.nodes[0].name = "left wing";
  m.nodes[0].mesh = 0;
  m.nodes[0].rotation = {0, std::sqrt(0.5), 0, std::sqrt(0.5)};
  m.nodes[0].scale = {2, 2, 2};
  m.nodes[1].name = "DEF";
  m.nodes[1].mesh = 0;
  m.nodes[1].matrix = {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1};
  m.nodes[1].children = {2};
  m.nodes[2].mesh = 1;
  m.scenes.emplace_back().nodes = {0, 1};
  m.defaultScene = 0;
  return m;
}

// The world-space triangles the VRML97 scene draws, as our reader reads the
// written text.
FlatVrml97 drawn(const scene::Scene& s) {
  const vrml97::ReadResult back = vrml97::read_vrml97(vrml97::write_vrml97(s));
  Log log;
  return flatten_vrml97(back.scene, {}, log);
}

// The triangles' area, area-weighted centroid and second moments about the
// origin: the same for the same triangles in any order.
std::array<double, 10> moments(const TriangleMesh& mesh) {
  std::array<double, 10> m{};
  for (const Triangle& t : mesh.triangles) {
    const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    const double area = 0.5 * length(cross(b - a, c - a));
    const Vec3 g = (a + b + c) / 3.0f;
    const double x = g.x, y = g.y, z = g.z;
    const std::array<double, 10> add{1, x, y, z, x * x, y * y, z * z, x * y, x * z, y * z};
    for (std::size_t k = 0; k < 10; ++k) m[k] += area * add[k];
  }
  return m;
}

// `got` draws the triangles of `want` in the same places (in any order).
void expect_same_places(const TriangleMesh& want, const TriangleMesh& got) {
  ASSERT_EQ(got.triangle_count(), want.triangle_count());
  const auto w = moments(want), g = moments(got);
  const double size = std::max(1.0f, want.bounds().diagonal());
  for (std::size_t k = 0; k < 10; ++k) {
    const double scale = w[0] * (k == 0 ? 1 : k < 4 ? size : size * size);
    EXPECT_NEAR(w[k], g[k], 1e-4 * scale) << "moment " << k;
  }
}

TEST(GltfToVrml97, NodesAreTransformsAndASharedMeshIsOneShape) {
  const tinygltf::Model m = two_nodes_one_mesh();
  Log log;
  const scene::Scene s = gltf_to_vrml97(m, log);
  EXPECT_EQ(s.header, "#VRML V2.0 utf8");
  ASSERT_EQ(s.roots.size(), 2u);
  EXPECT_EQ(s.roots[0]->type, "Transform");
  EXPECT_EQ(s.roots[0]->name, "left_wing");
  EXPECT_EQ(s.roots[1]->name, "DEF_");  // a keyword is no DEF name
  const auto* rotation = s.roots[0]->value("rotation");
  ASSERT_NE(rotation, nullptr);
  EXPECT_NEAR(rotation->floats[1], 1, 1e-6);
  EXPECT_NEAR(rotation->floats[3], M_PI / 2, 1e-6);
  const auto* scale = s.roots[1]->value("scale");
  ASSERT_NE(scale, nullptr);
  EXPECT_EQ(scale->floats, (std::vector<float>{-1, 1, 1}));
  // Both nodes hold the same Shape; node 2 is node 1's child.
  const auto& first = s.roots[0]->value("children")->nodes;
  const auto& second = s.roots[1]->value("children")->nodes;
  ASSERT_EQ(first.size(), 1u);
  ASSERT_EQ(second.size(), 2u);
  EXPECT_EQ(first[0], second[0]);
  EXPECT_EQ(second[1]->type, "Transform");
  // The places of every triangle, as a glTF viewer draws them.
  expect_same_places(scene_mesh(m), drawn(s).flat.mesh);
}

TEST(GltfToVrml97, MaterialsTexturesAndLinesLookAsInTheGltf) {
  Log log;
  const scene::Scene s = gltf_to_vrml97(two_nodes_one_mesh(), log);
  const auto shape = s.roots[0]->value("children")->nodes[0];
  const auto geometry = shape->value("geometry")->nodes[0];
  EXPECT_EQ(geometry->type, "IndexedFaceSet");
  EXPECT_EQ(geometry->value("coordIndex")->ints, (std::vector<std::int32_t>{0, 1, 2, -1}));
  EXPECT_EQ(geometry->value("solid")->ints, (std::vector<std::int32_t>{0}));  // double-sided
  // t = 1 - v: glTF's v runs down the image, VRML's t up.
  EXPECT_EQ(geometry->value("texCoord")->nodes[0]->value("point")->floats,
            (std::vector<float>{0, 1, 1, 1, 0, 0.75f}));
  const auto appearance = shape->value("appearance")->nodes[0];
  const auto material = appearance->value("material")->nodes[0];
  EXPECT_EQ(material->value("diffuseColor")->floats, (std::vector<float>{0.5f, 0.25f, 1}));
  EXPECT_FLOAT_EQ(material->value("transparency")->floats[0], 0.5f);
  const auto texture = appearance->value("texture")->nodes[0];
  EXPECT_EQ(texture->value("url")->strings,
            (std::vector<std::string>{"data:image/png;base64,iVBORwECAw=="}));
  EXPECT_EQ(texture->value("repeatS")->ints, (std::vector<std::int32_t>{0}));
  EXPECT_EQ(texture->value("repeatT"), nullptr);
  // The line: an IndexedLineSet drawn in the emissive colour.
  const auto line = s.roots[1]->value("children")->nodes[1]->value("children")->nodes[0];
  EXPECT_EQ(line->value("geometry")->nodes[0]->type, "IndexedLineSet");
  EXPECT_EQ(line->value("geometry")->nodes[0]->value("coordIndex")->ints,
            (std::vector<std::int32_t>{0, 1, -1}));
  const auto line_material = line->value("appearance")->nodes[0]->value("material")->nodes[0];
  EXPECT_EQ(line_material->value("emissiveColor")->floats, (std::vector<float>{0.5f, 0.25f, 1}));
  EXPECT_TRUE(log.entries().empty());
}

TEST(GltfToVrml97, WhatVrml97CannotHoldIsNamed) {
  tinygltf::Model m = two_nodes_one_mesh();
  m.animations.emplace_back();
  m.skins.emplace_back();
  m.nodes[0].skin = 0;
  m.nodes[1].matrix[1] = 0.5;  // a shear
  Log log;
  gltf_to_vrml97(m, log);
  ASSERT_EQ(log.entries().size(), 1u);
  const std::string& w = log.entries()[0].text;
  EXPECT_NE(w.find("animations (1)"), std::string::npos) << w;
  EXPECT_NE(w.find("skins"), std::string::npos) << w;
  EXPECT_NE(w.find("shear"), std::string::npos) << w;
}

TEST(GltfToVrml97, DeepHierarchiesAreRefused) {
  tinygltf::Model m = two_nodes_one_mesh();
  m.nodes.resize(3 + 300);
  m.nodes[2].children = {3};
  for (std::size_t i = 3; i + 1 < m.nodes.size(); ++i) m.nodes[i].children = {int(i + 1)};
  Log log;
  EXPECT_THROW(gltf_to_vrml97(m, log), DataError);
}

class GltfToVrml97Corpus : public ::testing::TestWithParam<std::string> {};

// Every corpus scene: the VRML97 scene, written and read back, draws the
// triangles the glTF scene draws, where it draws them.
TEST_P(GltfToVrml97Corpus, DrawsTheSameTrianglesInTheSamePlaces) {
  const GltfReadResult r = read_gltf_file(GetParam());
  Log log;
  const scene::Scene s = gltf_to_vrml97(r.scene.model, log);
  expect_same_places(scene_mesh(r.scene.model), drawn(s).flat.mesh);
}

INSTANTIATE_TEST_SUITE_P(Corpus, GltfToVrml97Corpus,
                         ::testing::ValuesIn(testing::gltf_corpus_files()),
                         [](const auto& info) { return testing::gltf_test_name(info.param); });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(GltfToVrml97Corpus);

}  // namespace
}  // namespace lodforge::gltf
