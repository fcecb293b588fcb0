// Open Inventor scenes through the LOD pipeline: every .iv file of the shared
// corpus (../shared/data/inventor) reads; `lod` writes Inventor 2.1 that Coin
// reads, with Inventor LOD nodes; level 0 draws what the input draws (Coin
// counts the same triangles, degenerate ones aside); and lodforge's traversal
// meets the shapes Coin meets. Plus tiny scenes: Complexity bounds the
// primitives' levels, strips and quad meshes get simplified levels.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "lod/lod_test_support.h"
#include "lodforge/core/error.h"
#include "lodforge/lod/generate_lod.h"
#include "lodforge/scene/flatten_scene.h"
#include "lodforge/scene/inventor_shapes.h"
#include "lodforge/scene/statistics.h"
#include "tools/coin_probe_runner.h"
#include "vrml1/corpus.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;

// Triangles whose three corners are at three different points.
std::size_t distinct_triangles(const TriangleMesh& m) {
  std::size_t n = 0;
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    if (!(a == b) && !(b == c) && !(c == a)) ++n;
  }
  return n;
}

// Per shape type: shapes met and their distinct triangles, in the traversal
// at LOD child 0.
struct TypeCounts {
  std::map<std::string, std::size_t> shapes, triangles;
};

TypeCounts type_counts(const scene::Scene& s) {
  TypeCounts c;
  scene::traverse(s, [&](const scene::ShapeVisit& v) {
    ++c.shapes[v.shape.type];
    c.triangles[v.shape.type] += distinct_triangles(scene::shape_mesh(v));
  });
  return c;
}

std::size_t at(const std::map<std::string, std::size_t>& m, const std::string& k) {
  auto it = m.find(k);
  return it == m.end() ? 0 : it->second;
}

class InventorCorpus : public ::testing::TestWithParam<std::string> {};

TEST(InventorCorpusFiles, AllTwentyEightAreThere) {
  const auto files = lodforge::testing::all_inventor_test_files();
  if (files.empty()) GTEST_SKIP() << "no shared corpus at " << LODFORGE_SHARED_DATA;
  EXPECT_EQ(files.size(), 28u);
}

TEST_P(InventorCorpus, ReadsAndLodWritesInventorThatCoinReads) {
  const std::string& path = GetParam();
  vrml1::ReadResult in = vrml1::read_vrml1_file(path);  // every file reads
  ASSERT_TRUE(scene::is_inventor_header(in.scene.header));
  LodResult r = generate_lod(in.scene, {});
  EXPECT_EQ(r.scene.header, "#Inventor V2.1 ascii");
  const fs::path out =
      fs::temp_directory_path() / ("lodforge_inventor_lod_" + std::to_string(getpid()) + "_" +
                                   lodforge::testing::test_name_for(path) + ".iv");
  vrml1::write_vrml1_file(r.scene, out.string());
  const scene::Scene written = vrml1::read_vrml1_file(out.string()).scene;
  EXPECT_EQ(written.header, "#Inventor V2.1 ascii");
  lodforge::testing::expect_lod_structure(written);
  const std::size_t lods = at(scene::scene_statistics(written).node_counts, "LOD");
  lodforge::testing::expect_indices_in_range(written);
  // Level 0 draws the input (degenerate triangles aside).
  const std::size_t ours_in = distinct_triangles(scene::flatten_scene(in.scene));
  const std::size_t ours_out = distinct_triangles(scene::flatten_scene(written));
  EXPECT_EQ(ours_out, ours_in);
  for (const auto& s : r.shapes)
    for (std::size_t k = 1; k < s.levels.size(); ++k)
      EXPECT_LE(s.levels[k].triangles, s.levels[0].triangles) << s.type << " line " << s.line;

#ifdef LODFORGE_COIN_PROBE
  using lodforge::testing::run_coin_probe;
  const auto coin_in = run_coin_probe(path, std::chrono::seconds(120), 0);
  const auto coin_out = run_coin_probe(out.string(), std::chrono::seconds(120), 0);
  ASSERT_TRUE(coin_in.read) << "Coin cannot read the input: " << coin_in.why_rejected();
  ASSERT_TRUE(coin_out.read) << "Coin cannot read our output: " << coin_out.why_rejected();
  if (!coin_in.accepted()) {
    // Coin crashes drawing the input (materialbinding.iv, normalbinding.iv:
    // an IndexedFaceSet under PER_VERTEX_INDEXED without materialIndex /
    // normalIndex, which VRML 1.0 and Inventor allow). Level 0 is that node
    // as it was; Coin draws every other level.
    EXPECT_THAT(coin_in.why_rejected(), ::testing::HasSubstr("crashed"));
    const auto coin_level1 = run_coin_probe(out.string(), std::chrono::seconds(120), 1);
    EXPECT_TRUE(coin_level1.accepted()) << coin_level1.why_rejected();
    EXPECT_EQ(at(coin_level1.node_counts, "LOD"), lods);
    std::printf(
        "[inventor] %s: lod %zu LOD nodes; Coin crashes drawing the input and level 0, "
        "draws level 1: %zu triangles\n",
        lodforge::testing::test_name_for(path).c_str(), lods, coin_level1.triangles());
    fs::remove(out);
    return;
  }
  ASSERT_TRUE(coin_out.accepted()) << "Coin rejects our output: " << coin_out.why_rejected();
  EXPECT_EQ(at(coin_out.node_counts, "LOD"), lods);
  std::size_t coin_in_total = 0, coin_out_total = 0;
  for (const auto& [type, n] : coin_in.distinct_triangles) coin_in_total += n;
  for (const auto& [type, n] : coin_out.distinct_triangles) coin_out_total += n;
  // Coin draws level 0 as it draws the input.
  EXPECT_EQ(coin_out_total, coin_in_total);
  // lodforge meets the shapes Coin meets, and for all but the round
  // primitives (tessellated by each its own way) the same triangles.
  const TypeCounts ours = type_counts(in.scene);
  for (const char* type : {"IndexedFaceSet", "IndexedLineSet", "FaceSet", "TriangleStripSet",
                           "IndexedTriangleStripSet", "QuadMesh", "LineSet", "PointSet", "Cube",
                           "Sphere", "Cone", "Cylinder"})
    EXPECT_EQ(at(ours.shapes, type), at(coin_in.primitive_counts, type)) << type;
  for (const char* type : {"IndexedFaceSet", "FaceSet", "TriangleStripSet",
                           "IndexedTriangleStripSet", "QuadMesh", "Cube"})
    EXPECT_EQ(at(ours.triangles, type), at(coin_in.distinct_triangles, type)) << type;
  std::printf(
      "[inventor] %s: lod %zu LOD nodes; triangles at level 0: Coin input %zu, Coin "
      "output %zu, lodforge input %zu, output %zu\n",
      lodforge::testing::test_name_for(path).c_str(), lods, coin_in_total, coin_out_total, ours_in,
      ours_out);
#endif
  fs::remove(out);
}

INSTANTIATE_TEST_SUITE_P(Corpus, InventorCorpus,
                         ::testing::ValuesIn(lodforge::testing::all_inventor_test_files()),
                         [](const auto& info) {
                           return lodforge::testing::test_name_for(info.param);
                         });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(InventorCorpus);

scene::Scene iv(const std::string& body) {
  return vrml1::read_vrml1("#Inventor V2.1 ascii\n" + body, {.source_name = "t.iv"}).scene;
}

TEST(InventorLod, ComplexityStartsThePrimitivesLevels) {
  // The windmill's frame rods: Complexity 0. No level may draw more than the
  // input does, and level 0 counts what the input draws.
  for (const char* c : {"0", "0.2", "0.5", "1"}) {
    const scene::Scene s = iv(std::string("Separator { Complexity { value ") + c +
                              " } Cylinder { } Sphere { } Cone { } }");
    const LodResult r = generate_lod(s, {});
    ASSERT_EQ(r.shapes.size(), 3u);
    std::size_t level0 = 0;
    for (const auto& sh : r.shapes) {
      ASSERT_FALSE(sh.levels.empty());
      level0 += sh.levels[0].triangles;
      for (std::size_t k = 1; k < sh.levels.size(); ++k)
        EXPECT_LT(sh.levels[k].triangles, sh.levels[0].triangles) << sh.type << " at " << c;
    }
    EXPECT_EQ(level0, scene::scene_statistics(s).total_triangles) << c;
  }
  // At complexity 0 a Cylinder has 4 segments (16 triangles); a coarser
  // level has 3 at most.
  const LodResult coarse = generate_lod(iv("Separator { Complexity { value 0 } Cylinder { } }"));
  EXPECT_EQ(coarse.shapes.at(0).levels.at(0).triangles, 16u);
  for (std::size_t k = 1; k < coarse.shapes[0].levels.size(); ++k)
    EXPECT_LE(coarse.shapes[0].levels[k].triangles, 12u);
  // At 1, the first coarser level is two thirds of the segments.
  const LodResult fine = generate_lod(iv("Separator { Complexity { value 1 } Cylinder { } }"));
  ASSERT_GE(fine.shapes.at(0).levels.size(), 2u);
  EXPECT_EQ(fine.shapes.at(0).levels[0].triangles, 4u * 48u);
  EXPECT_EQ(fine.shapes.at(0).levels[1].triangles, 4u * 32u);
}

TEST(InventorLod, StripsAndQuadMeshesGetSimplifiedLevels) {
  // A 21 x 21 quad mesh of a bumpy surface, given by a vertexProperty.
  std::string pts;
  for (int r = 0; r < 21; ++r)
    for (int c = 0; c < 21; ++c)
      pts += fmt::format("{} {} {},", c, 0.3 * std::sin(c * 0.5) * std::cos(r * 0.4), r);
  const scene::Scene s = iv("Separator { QuadMesh { vertexProperty VertexProperty { vertex [ " +
                            pts + " ] } verticesPerRow 21 verticesPerColumn 21 } }");
  const LodResult r = generate_lod(s, {});
  ASSERT_EQ(r.shapes.size(), 1u);
  EXPECT_EQ(r.shapes[0].type, "QuadMesh");
  EXPECT_EQ(r.shapes[0].levels.at(0).triangles, 800u);
  EXPECT_GE(r.shapes[0].levels.size(), 3u);
  // Level 0 is the QuadMesh itself; the others are IndexedFaceSets.
  const std::string text = vrml1::write_vrml1(r.scene);
  EXPECT_TRUE(text.starts_with("#Inventor V2.1 ascii\n"));
  EXPECT_NE(text.find("QuadMesh {"), std::string::npos);
  EXPECT_NE(text.find("LOD {"), std::string::npos);
  const scene::Scene back = vrml1::read_vrml1(text).scene;
  EXPECT_EQ(scene::flatten_scene(back).triangle_count(), 800u);
  EXPECT_LT(scene::flatten_scene(back, {.lod_level = 1}).triangle_count(), 800u);
}

}  // namespace
}  // namespace lodforge
