// gltf_lod: levels in MSFT_lod form on a small model built in memory.
#include "lodforge/lod/gltf_lod.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gltf/gltf_builder.h"
#include "lodforge/io/gltf/accessor_data.h"

namespace lodforge {
namespace {

using testing::add_floats;
using testing::add_indices;

// A wavy 40 x 40 grid (3 042 triangles) with normals and texture
// coordinates, as mesh 0 of `m`; returns the mesh's index.
int add_wavy_grid(tinygltf::Model& m) {
  const int n = 40;
  std::vector<float> p, nrm, uv;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = float(i) / n, y = float(j) / n;
      p.insert(p.end(), {x, y, 0.05f * std::sin(9 * x) * std::cos(7 * y)});
      nrm.insert(nrm.end(), {0, 0, 1});
      uv.insert(uv.end(), {x, y});
    }
  std::vector<std::uint32_t> idx;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = std::uint32_t(j * (n + 1) + i), b = a + 1, c = a + n + 1, d = c + 1;
      idx.insert(idx.end(), {a, b, d, a, d, c});
    }
  tinygltf::Primitive prim;
  prim.attributes["POSITION"] = add_floats(m, p, TINYGLTF_TYPE_VEC3);
  prim.attributes["NORMAL"] = add_floats(m, nrm, TINYGLTF_TYPE_VEC3);
  prim.attributes["TEXCOORD_0"] = add_floats(m, uv, TINYGLTF_TYPE_VEC2);
  prim.indices = add_indices(m, idx);
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.material = 0;
  tinygltf::Mesh mesh;
  mesh.name = "grid";
  mesh.primitives.push_back(prim);
  m.meshes.push_back(mesh);
  return int(m.meshes.size() - 1);
}

// Two nodes share the grid (the second scaled 2x); a third draws a copy of
// it with a morph target.
gltf::GltfScene shared_and_morphed() {
  gltf::GltfScene s;
  auto& m = s.model;
  m.materials.emplace_back();
  const int grid = add_wavy_grid(m);
  tinygltf::Mesh morphed = m.meshes[std::size_t(grid)];
  morphed.name = "morphed";
  morphed.primitives[0].targets.push_back(
      {{"POSITION", morphed.primitives[0].attributes["POSITION"]}});
  m.meshes.push_back(morphed);
  tinygltf::Node a, b, c;
  a.mesh = grid;
  b.mesh = grid;
  b.scale = {2, 2, 2};
  c.mesh = 1;
  m.nodes = {a, b, c};
  tinygltf::Scene scene;
  scene.nodes = {0, 1, 2};
  m.scenes.push_back(scene);
  return s;
}

const tinygltf::Value::Array& ids_of(const tinygltf::Node& node) {
  return node.extensions.at("MSFT_lod").Get("ids").Get<tinygltf::Value::Array>();
}

TEST(GltfLod, SharedMeshGetsOneSetOfLevelMeshesAndEachNodeItsLevelNodes) {
  gltf::GltfScene s = shared_and_morphed();
  const tinygltf::Mesh input = s.model.meshes[0];
  const LodResult r = gltf_lod(s, {.threads = 1});
  const auto& m = s.model;
  const auto& a = ids_of(m.nodes[0]);
  const auto& b = ids_of(m.nodes[1]);
  ASSERT_GE(a.size(), 2u);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    const auto& la = m.nodes[std::size_t(a[k].GetNumberAsInt())];
    const auto& lb = m.nodes[std::size_t(b[k].GetNumberAsInt())];
    EXPECT_EQ(la.mesh, lb.mesh);            // one level mesh for both nodes
    EXPECT_EQ(lb.scale, m.nodes[1].scale);  // each level node where its node is
    EXPECT_TRUE(la.children.empty());
  }
  // Level 0 is the input unchanged; MSFT_lod is used, not required.
  EXPECT_EQ(m.meshes[0], input);
  EXPECT_EQ(m.extensionsUsed, std::vector<std::string>{"MSFT_lod"});
  EXPECT_TRUE(m.extensionsRequired.empty());
  // The morphed mesh gets levels too, without a warning.
  EXPECT_EQ(m.nodes[2].extensions.count("MSFT_lod"), 1u);
  EXPECT_TRUE(r.log.entries().empty());
  // Switch distances scale with the node, coverages do not and decrease.
  const auto& ea = m.nodes[0].extras.Get("lodforge_lod").Get("levels");
  const auto& eb = m.nodes[1].extras.Get("lodforge_lod").Get("levels");
  for (int k = 1; k < int(ea.ArrayLen()); ++k)
    EXPECT_NEAR(eb.Get(k).Get("switch_distance").GetNumberAsDouble(),
                2 * ea.Get(k).Get("switch_distance").GetNumberAsDouble(), 1e-9);
  const auto& ca = m.nodes[0].extras.Get("MSFT_screencoverage");
  const auto& cb = m.nodes[1].extras.Get("MSFT_screencoverage");
  ASSERT_EQ(ca.ArrayLen(), a.size() + 1);
  for (int k = 0; k < int(ca.ArrayLen()); ++k) {
    EXPECT_DOUBLE_EQ(ca.Get(k).GetNumberAsDouble(), cb.Get(k).GetNumberAsDouble());
    if (k > 0) EXPECT_LT(ca.Get(k).GetNumberAsDouble(), ca.Get(k - 1).GetNumberAsDouble());
  }
}

TEST(GltfLod, ExtractDrawsOneLevelInPlaceOfEachMesh) {
  // --extract K: every node draws level K's mesh (the one MSFT_lod names as
  // level K), no MSFT_lod; 0 leaves the model as it is; beyond the last
  // level, the last.
  gltf::GltfScene full = shared_and_morphed();
  gltf_lod(full, {.threads = 1});
  const auto& ids = ids_of(full.model.nodes[0]);
  ASSERT_GE(ids.size(), 2u);
  auto level_mesh = [&](std::size_t k) {
    return full.model.nodes[std::size_t(ids[k - 1].GetNumberAsInt())].mesh;
  };
  for (int k : {0, 1, 2, 50}) {
    gltf::GltfScene s = shared_and_morphed();
    const tinygltf::Model input = s.model;
    gltf_lod(s, {.extract = k, .threads = 1});
    const auto& m = s.model;
    EXPECT_TRUE(m.extensionsUsed.empty()) << k;
    ASSERT_EQ(m.nodes.size(), 3u) << k;  // no level nodes
    for (const auto& node : m.nodes) EXPECT_EQ(node.extensions.count("MSFT_lod"), 0u);
    if (k == 0) {
      EXPECT_EQ(m.meshes, input.meshes);
      EXPECT_EQ(m.nodes, input.nodes);
      continue;
    }
    const std::size_t level = std::min<std::size_t>(std::size_t(k), ids.size());
    EXPECT_EQ(m.nodes[0].mesh, m.nodes[1].mesh);  // the shared mesh's one level
    ASSERT_GE(m.nodes[0].mesh, 0);
    EXPECT_EQ(m.meshes[std::size_t(m.nodes[0].mesh)],
              full.model.meshes[std::size_t(level_mesh(level))])
        << k;
  }
}

TEST(GltfLod, GivenRangesAreTheSwitchDistances) {
  // --ranges 0.5,0.75: the first two switch distances (mesh units; a node
  // scaled 2x switches at twice them), the rest computed and above them.
  gltf::GltfScene s = shared_and_morphed();
  LodOptions o{.threads = 1};
  o.manual["polygon"].ranges = {0.5f, 0.75f};
  gltf_lod(s, o);
  const auto& a = s.model.nodes[0].extras.Get("lodforge_lod").Get("levels");
  const auto& b = s.model.nodes[1].extras.Get("lodforge_lod").Get("levels");
  ASSERT_GE(a.ArrayLen(), 4u);
  EXPECT_DOUBLE_EQ(a.Get(1).Get("switch_distance").GetNumberAsDouble(), 0.5);
  EXPECT_DOUBLE_EQ(a.Get(2).Get("switch_distance").GetNumberAsDouble(), 0.75);
  EXPECT_DOUBLE_EQ(b.Get(1).Get("switch_distance").GetNumberAsDouble(), 1.0);
  EXPECT_GT(a.Get(3).Get("switch_distance").GetNumberAsDouble(), 0.75);
  // Screen coverages follow: radius / (distance tan(angle / 2)).
  const auto& c = s.model.nodes[0].extras.Get("MSFT_screencoverage");
  EXPECT_NEAR(c.Get(0).GetNumberAsDouble() * 0.5, c.Get(1).GetNumberAsDouble() * 0.75, 1e-9);
}

TEST(GltfLod, SmallerMeshesGetFewerLevelsWhenDifferentiatedBySize) {
  // The grid drawn at full size and a copy of it at a quarter (node scale):
  // --quality polygon=5 --differentiate-by-size asks 3 halvings of the large
  // one (those the spacing rule keeps are written) and of the small one, two
  // halvings smaller, 1.
  gltf::GltfScene s;
  auto& m = s.model;
  m.materials.emplace_back();
  const int grid = add_wavy_grid(m);
  m.meshes.push_back(m.meshes[std::size_t(grid)]);
  tinygltf::Node a, b;
  a.mesh = grid;
  b.mesh = grid + 1;
  b.scale = {0.25, 0.25, 0.25};
  m.nodes = {a, b};
  tinygltf::Scene scene;
  scene.nodes = {0, 1};
  m.scenes.push_back(scene);
  LodOptions o{.differentiate_by_size = true, .threads = 1};
  o.manual["polygon"] = {.quality = 5};
  gltf::GltfScene sized = s;
  const LodResult r = gltf_lod(sized, o);
  ASSERT_EQ(r.shapes.size(), 2u);
  EXPECT_EQ(r.shapes[1].levels.size(), 2u);  // level 0 and one halving
  EXPECT_EQ(ids_of(sized.model.nodes[1]).size(), 1u);
  EXPECT_GT(r.shapes[0].levels.size(), 2u);
  o.differentiate_by_size = false;
  const LodResult same = gltf_lod(s, o);
  EXPECT_EQ(same.shapes[1].levels.size(), r.shapes[0].levels.size());
}

TEST(GltfLod, MeshesInParallelGiveTheOneThreadModel) {
  gltf::GltfScene one = shared_and_morphed(), all = shared_and_morphed();
  const LodResult r1 = gltf_lod(one, {.threads = 1});
  const LodResult r0 = gltf_lod(all, {.threads = 0});
  EXPECT_EQ(all.model, one.model);
  ASSERT_EQ(r0.shapes.size(), r1.shapes.size());
  for (std::size_t i = 0; i < r0.shapes.size(); ++i)
    EXPECT_EQ(r0.shapes[i].ranges, r1.shapes[i].ranges);
}

TEST(GltfLod, LevelsShareOneVertexSetWhoseAddedVerticesCopyTheirSourcesAttributes) {
  gltf::GltfScene s = shared_and_morphed();
  gltf_lod(s, {.threads = 1});
  const auto& m = s.model;
  const auto& ids = ids_of(m.nodes[0]);
  const auto& first = m.meshes[std::size_t(m.nodes[std::size_t(ids[0].GetNumberAsInt())].mesh)];
  const auto& input = m.meshes[0].primitives[0];
  const auto in_uv = gltf::read_accessor(m, input.attributes.at("TEXCOORD_0")).values;
  const std::size_t n = in_uv.size() / 2;
  for (const auto& id : ids) {
    const auto& level = m.meshes[std::size_t(m.nodes[std::size_t(id.GetNumberAsInt())].mesh)];
    ASSERT_EQ(level.primitives.size(), 1u);
    const auto& p = level.primitives[0];
    EXPECT_EQ(p.mode, TINYGLTF_MODE_TRIANGLES);
    EXPECT_EQ(p.material, input.material);
    EXPECT_EQ(p.attributes, first.primitives[0].attributes);  // one vertex set for all levels
    EXPECT_NE(p.indices, input.indices);
  }
  const auto& attributes = first.primitives[0].attributes;
  const auto uv = gltf::read_accessor(m, attributes.at("TEXCOORD_0")).values;
  const auto normals = gltf::read_accessor(m, attributes.at("NORMAL")).values;
  // Only the vertices the levels draw (the input's are not copied): fewer
  // than the input's; every one carries the texture coordinates of an input
  // vertex and the input's normal.
  ASSERT_GT(uv.size(), 0u);
  EXPECT_LT(uv.size() / 2, n);
  for (std::size_t v = 0; v < uv.size() / 2; ++v) {
    const double u = uv[2 * v], w = uv[2 * v + 1];
    EXPECT_NEAR(u * 40, std::round(u * 40), 1e-4) << v;
    EXPECT_NEAR(w * 40, std::round(w * 40), 1e-4) << v;
    EXPECT_EQ(normals[3 * v + 2], 1.0);
  }
}

// The morphed grid also skinned (two joints, weights by x) and its morph
// weights animated.
gltf::GltfScene morphed_skinned_animated() {
  gltf::GltfScene s = shared_and_morphed();
  auto& m = s.model;
  tinygltf::Primitive& p = m.meshes[1].primitives[0];
  const auto positions = gltf::read_accessor(m, p.attributes.at("POSITION")).values;
  std::vector<float> weights;
  std::vector<std::uint16_t> joints;
  for (std::size_t v = 0; v < positions.size() / 3; ++v) {
    const auto x = float(positions[3 * v]);
    weights.insert(weights.end(), {x, 1 - x, 0, 0});
    joints.insert(joints.end(), {0, 1, 0, 0});
  }
  p.attributes["WEIGHTS_0"] = testing::add_floats(m, weights, TINYGLTF_TYPE_VEC4);
  p.attributes["JOINTS_0"] =
      testing::add_accessor(m, joints, TINYGLTF_TYPE_VEC4, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  m.nodes.resize(5);  // nodes 3 and 4: the joints
  tinygltf::Skin skin;
  skin.joints = {3, 4};
  m.skins.push_back(skin);
  m.nodes[2].skin = 0;
  m.scenes[0].nodes.insert(m.scenes[0].nodes.end(), {3, 4});
  tinygltf::Animation a;
  tinygltf::AnimationSampler sampler;
  sampler.input = testing::add_floats(m, {0, 1}, TINYGLTF_TYPE_SCALAR);
  sampler.output = testing::add_floats(m, {0, 1}, TINYGLTF_TYPE_SCALAR);
  a.samplers.push_back(sampler);
  tinygltf::AnimationChannel channel;
  channel.sampler = 0;
  channel.target_node = 2;
  channel.target_path = "weights";
  a.channels.push_back(channel);
  m.animations.push_back(a);
  return s;
}

// A level vertex of a skinned, morphed mesh carries one input vertex's joints,
// weights and morph displacement; its level nodes have the node's skin and
// the animation of its morph weights.
TEST(GltfLod, SkinsMorphTargetsAndTheirAnimationsFollowTheLevels) {
  gltf::GltfScene s = morphed_skinned_animated();
  const LodResult r = gltf_lod(s, {.threads = 1});
  EXPECT_TRUE(r.log.entries().empty());
  const auto& m = s.model;
  const auto& ids = ids_of(m.nodes[2]);
  ASSERT_GE(ids.size(), 2u);
  for (const auto& id : ids) {
    const int level = id.GetNumberAsInt();
    EXPECT_EQ(m.nodes[std::size_t(level)].skin, 0);
    EXPECT_EQ(std::count_if(m.animations[0].channels.begin(), m.animations[0].channels.end(),
                            [&](const auto& c) {
                              return c.target_node == level && c.target_path == "weights";
                            }),
              1);
    const tinygltf::Primitive& p =
        m.meshes[std::size_t(m.nodes[std::size_t(level)].mesh)].primitives[0];
    ASSERT_EQ(p.targets.size(), 1u);
    const auto count = m.accessors[std::size_t(p.attributes.at("POSITION"))].count;
    for (const char* name : {"JOINTS_0", "WEIGHTS_0"})
      EXPECT_EQ(m.accessors[std::size_t(p.attributes.at(name))].count, count) << name;
    const tinygltf::Accessor& displacement = m.accessors[std::size_t(p.targets[0].at("POSITION"))];
    EXPECT_EQ(displacement.count, count);
    EXPECT_EQ(displacement.minValues.size(), 3u);  // required of a target's POSITION
    // Displacement = the source's position (the target is the grid itself),
    // weights = (x, 1 - x) of the same source, joints unchanged.
    const auto d = gltf::read_accessor(m, p.targets[0].at("POSITION")).values;
    const auto w = gltf::read_accessor(m, p.attributes.at("WEIGHTS_0")).values;
    const auto j = gltf::read_accessor(m, p.attributes.at("JOINTS_0")).values;
    for (std::size_t v = 0; v < count; ++v) {
      EXPECT_NEAR(d[3 * v] * 40, std::round(d[3 * v] * 40), 1e-4) << v;
      EXPECT_NEAR(w[4 * v], d[3 * v], 1e-6) << v;
      EXPECT_NEAR(w[4 * v + 1], 1 - d[3 * v], 1e-6) << v;
      EXPECT_EQ(j[4 * v + 1], 1) << v;
    }
  }
}

// A wavy 40 x 40 grid textured as two islands: u = x in [0, 0.5] left of
// x = 0.5, u = 1.6 - x in [0.6, 1.1] right of it; the seam column's vertices
// are doubled, one per island.
gltf::GltfScene seamed_grid() {
  gltf::GltfScene s;
  auto& m = s.model;
  const int n = 40, half = n / 2;
  std::vector<float> p, uv;
  auto vertex = [&](int i, int j, bool right) {
    const float x = float(i) / n, y = float(j) / n;
    p.insert(p.end(), {x, y, 0.05f * std::sin(9 * x) * std::cos(7 * y)});
    uv.insert(uv.end(), {right ? 1.6f - x : x, y});
    return std::uint32_t(p.size() / 3 - 1);
  };
  std::vector<std::uint32_t> left((half + 1) * (n + 1)), right((n - half + 1) * (n + 1));
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= half; ++i) left[std::size_t(j * (half + 1) + i)] = vertex(i, j, false);
    for (int i = half; i <= n; ++i)
      right[std::size_t(j * (n - half + 1) + i - half)] = vertex(i, j, true);
  }
  std::vector<std::uint32_t> idx;
  auto cells = [&](const std::vector<std::uint32_t>& v, int columns) {
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < columns; ++i) {
        const auto at = [&](int a, int b) { return v[std::size_t(b * (columns + 1) + a)]; };
        idx.insert(idx.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1),
                               at(i, j + 1)});
      }
  };
  cells(left, half);
  cells(right, n - half);
  tinygltf::Primitive prim;
  prim.attributes["POSITION"] = testing::add_floats(m, p, TINYGLTF_TYPE_VEC3);
  prim.attributes["TEXCOORD_0"] = testing::add_floats(m, uv, TINYGLTF_TYPE_VEC2);
  prim.indices = testing::add_indices(m, idx);
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.material = 0;  // a base-colour texture on TEXCOORD_0
  m.materials.emplace_back();
  m.materials[0].pbrMetallicRoughness.baseColorTexture.index = 0;
  m.textures.emplace_back();
  tinygltf::Mesh mesh;
  mesh.primitives.push_back(prim);
  m.meshes.push_back(mesh);
  m.nodes.emplace_back();
  m.nodes[0].mesh = 0;
  tinygltf::Scene scene;
  scene.nodes = {0};
  m.scenes.push_back(scene);
  return s;
}

// Every corner of a level triangle takes its texture coordinates from the
// island the triangle lies on: the simplifier keeps the seams of texture
// coordinates a texture uses, so a level vertex's source vertex is on its
// triangle's side of the seam.
TEST(GltfLod, LevelTrianglesKeepTheirTextureIsland) {
  gltf::GltfScene s = seamed_grid();
  gltf_lod(s, {.threads = 1});
  const auto& m = s.model;
  const auto& ids = ids_of(m.nodes[0]);
  ASSERT_GE(ids.size(), 2u);
  for (const auto& id : ids) {
    const auto& p =
        m.meshes[std::size_t(m.nodes[std::size_t(id.GetNumberAsInt())].mesh)].primitives[0];
    const auto xyz = gltf::read_accessor(m, p.attributes.at("POSITION")).values;
    const auto uv = gltf::read_accessor(m, p.attributes.at("TEXCOORD_0")).values;
    const auto idx = gltf::read_accessor(m, p.indices).values;
    std::size_t wrong = 0;
    for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
      double cx = 0;
      for (int k = 0; k < 3; ++k) cx += xyz[3 * std::size_t(idx[t + std::size_t(k)])] / 3;
      for (int k = 0; k < 3; ++k) {
        const double u = uv[2 * std::size_t(idx[t + std::size_t(k)])];
        if (cx < 0.5 ? u > 0.5 + 1e-4 : u < 0.6 - 1e-4) ++wrong;
      }
    }
    EXPECT_EQ(wrong, 0u) << "level node " << id.GetNumberAsInt() << ", " << idx.size() / 3
                         << " triangles";
  }
}

// A flat-shaded grid (three vertices per triangle, each with the face's
// normal and its own texture coordinates, no texture) still gets levels:
// normals and untextured coordinates are no seams the simplifier keeps.
TEST(GltfLod, FlatShadedUntexturedMeshGetsLevels) {
  gltf::GltfScene s = shared_and_morphed();
  auto& m = s.model;
  tinygltf::Primitive& prim = m.meshes[0].primitives[0];
  const auto p = gltf::read_accessor(m, prim.attributes.at("POSITION")).values;
  const auto idx = gltf::read_accessor(m, prim.indices).values;
  std::vector<float> xyz, nrm, uv;
  std::vector<std::uint32_t> flat;
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
    Vec3 c[3];
    for (int k = 0; k < 3; ++k) {
      const auto v = std::size_t(idx[t + std::size_t(k)]);
      c[k] = {float(p[3 * v]), float(p[3 * v + 1]), float(p[3 * v + 2])};
    }
    const Vec3 n = normalized(cross(c[1] - c[0], c[2] - c[0]));
    for (int k = 0; k < 3; ++k) {
      xyz.insert(xyz.end(), {c[k].x, c[k].y, c[k].z});
      nrm.insert(nrm.end(), {n.x, n.y, n.z});
      uv.insert(uv.end(), {float(k % 2), float(k / 2)});
      flat.push_back(std::uint32_t(flat.size()));
    }
  }
  prim.attributes = {{"POSITION", testing::add_floats(m, xyz, TINYGLTF_TYPE_VEC3)},
                     {"NORMAL", testing::add_floats(m, nrm, TINYGLTF_TYPE_VEC3)},
                     {"TEXCOORD_0", testing::add_floats(m, uv, TINYGLTF_TYPE_VEC2)}};
  prim.indices = testing::add_indices(m, flat);
  prim.material = -1;
  gltf_lod(s, {.threads = 1});
  ASSERT_EQ(m.nodes[0].extensions.count("MSFT_lod"), 1u);
  EXPECT_GE(ids_of(m.nodes[0]).size(), 2u);
}

TEST(GltfLod, CompressedVertexDataStaysWholeWithAWarning) {
  // Draco keeps the real vertices in its own stream: the accessors' data is not the mesh.
  gltf::GltfScene s = shared_and_morphed();
  for (auto& mesh : s.model.meshes)
    mesh.primitives[0].extensions["KHR_draco_mesh_compression"] =
        tinygltf::Value(tinygltf::Value::Object{});
  const LodResult r = gltf_lod(s, {.threads = 1});
  EXPECT_TRUE(s.model.nodes[0].extensions.empty());
  EXPECT_TRUE(s.model.extensionsUsed.empty());
  ASSERT_FALSE(r.log.entries().empty());
  EXPECT_NE(r.log.entries()[0].text.find(
                "mesh 0 'grid': kept at full detail because a primitive has the extension "
                "KHR_draco_mesh_compression"),
            std::string::npos)
      << r.log.entries()[0].text;
}

}  // namespace
}  // namespace lodforge
