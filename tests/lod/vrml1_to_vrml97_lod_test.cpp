// The bunny as a VRML 1.0 scene through the LOD pipeline, converted to VRML97
// (vrml97::vrml1_to_vrml97): Coin3D reads it with the input's 69 451
// triangles at level 0, the LOD keeps the VRML 1.0 ranges, and each written
// level's measured error is within the screen error its range promises.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/temp_dir.h"
#include "lod/lod_test_support.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/vrml97/vrml1_to_vrml97.h"
#include "lodforge/io/vrml97/write_vrml97.h"
#include "lodforge/mesh/mesh_io.h"
#include "tools/coin_probe_runner.h"

namespace lodforge {
namespace {

using scene::Node;

const scene::FieldValue& field(const Node& n, const char* name) {
  const scene::FieldValue* v = n.value(name);
  if (!v) throw std::runtime_error(std::string("no field ") + name + " in " + n.type);
  return *v;
}

// The triangles of the Shapes in a VRML97 LOD's level k (IndexedFaceSets of
// triangles, as the conversion writes them).
TriangleMesh level_mesh(const Node& lod, int k) {
  TriangleMesh mesh;
  const Node& group = *field(lod, "level").nodes.at(std::size_t(k));
  const scene::FieldValue* children = group.value("children");
  for (const auto& shape : children ? children->nodes : std::vector<scene::NodePtr>{}) {
    const Node& ifs = *field(*shape, "geometry").nodes.at(0);
    const auto& p = field(*field(ifs, "coord").nodes.at(0), "point").floats;
    const auto base = std::uint32_t(mesh.positions.size());
    for (std::size_t i = 0; i + 2 < p.size(); i += 3)
      mesh.positions.push_back({p[i], p[i + 1], p[i + 2]});
    const auto& index = field(ifs, "coordIndex").ints;
    for (std::size_t i = 0; i + 2 < index.size(); i += 4)
      mesh.triangles.push_back({base + std::uint32_t(index[i]), base + std::uint32_t(index[i + 1]),
                                base + std::uint32_t(index[i + 2])});
  }
  return mesh;
}

using Vrml1ToVrml97Lod = testing::TempDirTest;

TEST_F(Vrml1ToVrml97Lod, BunnyIsReadByCoinAndItsLevelsKeepTheirPromisedError) {
  const std::string ply = std::string(LODFORGE_SHARED_DATA) + "/meshes/bun_zipper.ply";
  if (!std::filesystem::exists(ply)) GTEST_SKIP() << "no " << ply;
  const std::string text = testing::scene_of(read_mesh(ply), "Scale { scaleFactor 10 10 10 }");
  LodResult r = generate_lod(vrml1::read_vrml1(text).scene, {.measure_samples = 30000});
  ASSERT_EQ(r.shapes.size(), 1u);
  ASSERT_GE(r.shapes[0].levels.size(), 5u);
  Log log;
  const scene::Scene converted = vrml97::vrml1_to_vrml97(r.scene, {}, log);
  const std::string out = path("bunny97.wrl");
  vrml97::write_vrml97_file(converted, out);

  const testing::CoinResult coin = testing::run_coin_probe(out, std::chrono::seconds(300), 0);
#ifdef LODFORGE_COIN_PROBE
  ASSERT_TRUE(coin.accepted()) << coin.why_rejected();
  EXPECT_EQ(coin.triangles(), 69451u);
  EXPECT_EQ(coin.node_counts.at("VRMLLOD"), 1u);
#endif

  // Read back: one LOD with the VRML 1.0 output's ranges (the bunny is
  // under the scale, so the centre moves, the distances do not).
  const scene::Scene back = vrml97::read_vrml97_file(out).scene;
  const Node* lod = nullptr;
  for (const auto& n : back.roots)
    if (n->type == "LOD") lod = n.get();
  ASSERT_NE(lod, nullptr);
  const std::vector<float> ranges = field(*lod, "range").floats;
  EXPECT_EQ(ranges, r.shapes[0].ranges);
  EXPECT_EQ(field(*lod, "level").nodes.size(), ranges.size() + 1);
  EXPECT_EQ(level_mesh(*lod, 0).triangle_count(), 69451u);
  testing::expect_level_errors_bounded(
      r, [&](int k) { return level_mesh(*lod, k); }, ranges, 0.02, 0.785398, 30000);
}

}  // namespace
}  // namespace lodforge
