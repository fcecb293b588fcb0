// `info`, `compare` and `render` on glTF scenes: per mesh and primitive
// counts, and the scene's triangles in world space at a chosen MSFT_lod level.
#include <gtest/gtest.h>

#include <fmt/core.h>

#include <nlohmann/json.hpp>

#include "apps/run_command.h"
#include "core/temp_dir.h"

namespace lodforge::testing {
namespace {

const std::string kTorus = std::string(LODFORGE_SHARED_DATA) +
                           "/gltf/castle-engine__demo-models/x3d/inline_geometry/torus.glb";

class GltfInfo : public TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    if (!std::filesystem::exists(kTorus)) GTEST_SKIP() << "corpus missing: " << kTorus;
  }
};

TEST_F(GltfInfo, CountsPerMeshAndPrimitiveAndMsftLodNodes) {
  const CommandResult in = run_lodforge("info --json " + kTorus);
  ASSERT_EQ(in.exit_code, 0) << in.err;
  const auto j = nlohmann::json::parse(in.out);
  EXPECT_EQ(j["meshes"][0]["primitives"][0]["triangles"], 1152);
  EXPECT_EQ(j["meshes"][0]["primitives"][0]["mode"], "TRIANGLES");
  EXPECT_EQ(j["triangles"], 1152);
  EXPECT_EQ(j["nodes_with_msft_lod"], 0);
  ASSERT_EQ(run_lodforge("lod " + kTorus + " -o " + path("t.glb") + " -q").exit_code, 0);
  const auto out = nlohmann::json::parse(run_lodforge("info --json " + path("t.glb")).out);
  EXPECT_EQ(out["nodes_with_msft_lod"], 1);
  EXPECT_EQ(out["triangles"], 1152);  // the scene draws level 0
}

TEST_F(GltfInfo, CompareAndRenderReadTheLevelsOfMsftLod) {
  ASSERT_EQ(
      run_lodforge("lod " + kTorus + " -o " + path("t.glb") + " --stats " + path("s.json") + " -q")
          .exit_code,
      0);
  const auto stats = nlohmann::json::parse(read_text(path("s.json")));
  // Level 0 of the output is the input.
  const auto same = nlohmann::json::parse(
      run_lodforge("compare --json " + kTorus + " " + path("t.glb") + " -q").out);
  EXPECT_EQ(same["hausdorff"], 0.0) << same.dump();
  // Level 1 is within the error the statistics state for it.
  const auto level1 = nlohmann::json::parse(
      run_lodforge("compare --json " + kTorus + " " + path("t.glb") + " --level 1 -q").out);
  EXPECT_GT(level1["hausdorff"].get<double>(), 0);
  EXPECT_LE(level1["hausdorff"].get<double>(),
            stats["shapes"][0]["levels"][1]["error"].get<double>());
  const CommandResult r =
      run_lodforge("render " + path("t.glb") + " -o " + path("t.png") + " --level 1");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find(fmt::format("{} triangles",
                                   stats["shapes"][0]["levels"][1]["triangles"].get<int>())),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace lodforge::testing
