// The LOD pipeline over the real corpus (../shared/data/vrml1) and the
// examples: Coin3D reads every output it read the input of; level 0 draws the
// input's triangles; levels shrink; LOD nodes are well formed; every index is
// in range for its binding.
#include <gtest/gtest.h>

#include <filesystem>

#include "lod/lod_test_support.h"
#include "lodforge/core/error.h"
#include "lodforge/lod/generate_lod.h"
#include "lodforge/metrics/compare_meshes.h"
#include "lodforge/scene/flatten_scene.h"
#include "lodforge/scene/statistics.h"
#include "tools/coin_probe_runner.h"
#include "vrml1/corpus.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;

// IndexedFaceSet triangles a renderer draws (n - 2 per face of n >= 3
// corners), leaving out faces the pipeline removes as degenerate: fewer than
// three corners once consecutive repeats are dropped.
std::size_t drawable_ifs_triangles(const scene::Scene& s) {
  std::size_t total = 0;
  scene::traverse(s, [&](const scene::ShapeVisit& v) {
    if (v.shape.type != "IndexedFaceSet") return;
    const auto& ci = scene::field_or_default(v.shape, "coordIndex")->ints;
    const scene::FieldValue* pts =
        v.state.coordinate3 ? scene::field_or_default(*v.state.coordinate3, "point") : nullptr;
    auto same = [&](std::int32_t a, std::int32_t b) {
      if (a == b) return true;
      if (!pts || std::size_t(std::max(a, b)) * 3 + 2 >= pts->floats.size()) return false;
      for (int k = 0; k < 3; ++k)
        if (pts->floats[3 * a + k] != pts->floats[3 * b + k]) return false;
      return true;
    };
    scene::for_each_index_run(ci, [&](std::size_t b, std::size_t e) {
      std::vector<std::int32_t> poly;
      for (std::size_t i = b; i < e; ++i)
        if (poly.empty() || !same(poly.back(), ci[i])) poly.push_back(ci[i]);
      while (poly.size() > 1 && same(poly.front(), poly.back())) poly.pop_back();
      if (poly.size() >= 3) total += poly.size() - 2;
    });
  });
  return total;
}

class LodCorpus : public ::testing::TestWithParam<std::string> {};

TEST_P(LodCorpus, OutputIsReadByCoinAndKeepsTheInputAtLevelZero) {
  const std::string& path = GetParam();
  vrml1::ReadResult in = vrml1::read_vrml1_file(path);
  LodResult r;
  try {
    r = generate_lod(in.scene, {});
  } catch (const DataError& e) {
    // Only broken geometry may stop the pipeline, with the line named.
    EXPECT_NE(std::string(e.what()).find("line "), std::string::npos) << e.what();
    GTEST_SKIP() << "input has broken geometry: " << e.what();
  }
  fs::path out =
      fs::temp_directory_path() / ("lodforge_lod_corpus_" + std::to_string(getpid()) + "_" +
                                   lodforge::testing::test_name_for(path) + ".wrl");
  vrml1::write_vrml1_file(r.scene, out.string());
  scene::Scene written = vrml1::read_vrml1_file(out.string()).scene;

  lodforge::testing::expect_lod_structure(written);
  lodforge::testing::expect_indices_in_range(written);
  // Level 0 of every LOD draws what the input drew (degenerate faces aside:
  // level 0 is the input node itself, or rebuilt without them).
  EXPECT_EQ(drawable_ifs_triangles(written), drawable_ifs_triangles(in.scene));
  for (const auto& s : r.shapes)
    for (std::size_t k = 1; k < s.levels.size(); ++k)
      EXPECT_LE(s.levels[k].triangles, s.levels[k - 1].triangles) << s.type << " line " << s.line;
  // Whole chains: a face set of 200 triangles or more ends at a quarter of
  // them at most, unless its coarsest level's error is already half of the
  // error at which the object vanishes (2 r).
  for (const auto& s : r.shapes) {
    if (s.type != "IndexedFaceSet" || s.levels.empty() || s.ranges.empty()) continue;
    if (s.levels[0].triangles < 200) continue;
    const LevelStatistics& coarsest = s.levels.back();
    EXPECT_TRUE(4 * coarsest.triangles <= s.levels[0].triangles || coarsest.error >= s.radius)
        << "line " << s.line << ": " << s.levels[0].triangles << " -> " << coarsest.triangles
        << " triangles, error " << coarsest.error << " of radius " << s.radius << " ("
        << s.stop_reason << ")";
  }

  // The deviation of level k from level 0, measured again (another seed, more
  // samples), is within the errors the ranges used. Over the whole scene the
  // Hausdorff distance is at most the largest of the shapes' (each point's
  // distance to the union is at most that to its own shape's level), so the
  // check runs at the levels every shape with faces still has.
  std::size_t common = SIZE_MAX;
  // (Files with LOD nodes of their own are left out: flattening at level k
  // would switch those too; the check is for ours.)
  for (const auto& s : r.shapes)
    if (s.type != "IndexedLineSet" && !s.levels.empty() && !s.ranges.empty())
      common = std::min(common, s.levels.size());
  TriangleMesh level0 = scene::flatten_scene(written, {.lod_level = 0});
  const bool own_lods = scene::scene_statistics(in.scene).node_counts["LOD"] > 0;
  for (std::size_t k = 1;
       !own_lods && common != SIZE_MAX && k < common && !level0.triangles.empty(); ++k) {
    double bound = 0;
    for (const auto& s : r.shapes)
      if (s.type != "IndexedLineSet" && !s.ranges.empty())
        bound = std::max(bound, s.levels[k].error * s.scale);
    TriangleMesh level = scene::flatten_scene(written, {.lod_level = int(k)});
    if (level.triangles.empty()) break;
    CompareResult c = compare_meshes(level0, level, {.samples = 20000, .seed = 99});
    EXPECT_LE(c.hausdorff, bound * (1 + 1e-6)) << "level " << k;
  }

#ifdef LODFORGE_COIN_PROBE
  lodforge::testing::CoinResult coin_in = lodforge::testing::run_coin_probe(path);
  if (coin_in.accepted()) {
    lodforge::testing::CoinResult coin_out = lodforge::testing::run_coin_probe(out.string());
    EXPECT_TRUE(coin_out.accepted()) << "Coin rejects our output: " << coin_out.why_rejected();
    EXPECT_EQ(coin_out.node_counts["LOD"], scene::scene_statistics(written).node_counts["LOD"]);
  }
#endif
  fs::remove(out);
}

INSTANTIATE_TEST_SUITE_P(Corpus, LodCorpus,
                         ::testing::ValuesIn(lodforge::testing::all_vrml_test_files()),
                         [](const auto& info) {
                           return lodforge::testing::test_name_for(info.param);
                         });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(LodCorpus);

}  // namespace
}  // namespace lodforge
