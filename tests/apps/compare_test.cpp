// `lodforge compare` as other tools run it: the JSON keys they read, VRML
// input with LOD levels, the coloured output, errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/run_command.h"
#include "lodforge/mesh/mesh_io.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::run_lodforge;

class CompareCli : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    scene_ = write("lod.wrl",
                   "#VRML V1.0 ascii\nSeparator { Translation { translation 5 0 0 }\n"
                   "LOD { range [ 10 ] Cube { } Cube { width 1 } } }\n");
  }
  std::string scene_;
};

TEST_F(CompareCli, JsonHasTheKeysOtherToolsRead) {
  auto r = run_lodforge("compare " + scene_ + " " + scene_ + " --level 1 --json --samples 20000");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  for (const char* k : {"hausdorff", "hausdorff_pct_diag", "a_to_b", "b_to_a", "normal"})
    EXPECT_TRUE(j.contains(k)) << k;
  for (const char* side : {"a_to_b", "b_to_a"})
    for (const char* k : {"max", "mean", "rms", "variance"}) EXPECT_TRUE(j[side].contains(k));
  for (const char* k : {"mean", "max", "variance"}) EXPECT_TRUE(j["normal"].contains(k));
  // Level 1 (width 1) against level 0 (width 2): the x faces are 0.5 apart.
  EXPECT_NEAR(j["hausdorff"].get<double>(), 0.5, 1e-4);
  EXPECT_EQ(j["a_triangles"].get<int>(), 12);
}

TEST_F(CompareCli, SameSceneSameLevelIsZeroAndColoredOutputIsWritten) {
  std::string colored = (dir_ / "colored.ply").string();
  auto r = run_lodforge("compare " + scene_ + " " + scene_ + " --json --colored " + colored);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["hausdorff"].get<double>(), 0.0);
  TriangleMesh m = read_mesh(colored);
  EXPECT_EQ(m.colors.size(), m.positions.size());
}

TEST_F(CompareCli, ColouredMeshesReportTheColourDeviation) {
  // One red and one blue triangle, the same surface: RGB distance sqrt 2.
  auto ply = [&](const char* name, const char* rgb) {
    std::string body = std::string(
                           "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                           "property float y\nproperty float z\nproperty uchar red\n"
                           "property uchar green\nproperty uchar blue\nelement face 1\n"
                           "property list uchar int vertex_indices\nend_header\n") +
                       "0 0 0 " + rgb + "\n1 0 0 " + rgb + "\n0 1 0 " + rgb + "\n3 0 1 2\n";
    return write(name, body);
  };
  std::string red = ply("red.ply", "255 0 0"), blue = ply("blue.ply", "0 0 255");
  auto r = run_lodforge("compare " + red + " " + blue + " --json --samples 1000");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  for (const char* side : {"a_to_b", "b_to_a"}) {
    ASSERT_TRUE(j[side].contains("color")) << side;
    EXPECT_NEAR(j[side]["color"]["mean"].get<double>(), std::sqrt(2.0), 1e-5);
  }
  auto plain = run_lodforge("compare " + scene_ + " " + scene_ + " --json --samples 1000");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_FALSE(nlohmann::json::parse(plain.out)["a_to_b"].contains("color"));
}

TEST_F(CompareCli, EmptySurfaceAndMissingFileAreErrors) {
  std::string empty = (dir_ / "empty.wrl").string();
  std::ofstream(empty) << "#VRML V1.0 ascii\nSeparator { }\n";
  auto r = run_lodforge("compare " + scene_ + " " + empty);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("empty"));
  EXPECT_EQ(run_lodforge("compare " + scene_ + " " + (dir_ / "none.ply").string()).exit_code, 1);
  EXPECT_EQ(run_lodforge("compare " + scene_).exit_code, 2);
}

}  // namespace
}  // namespace lodforge
