#include "lodforge/studio/lod_request.h"

#include <gtest/gtest.h>

#include "lodforge/core/error.h"

namespace lodforge::studio {
namespace {

using nlohmann::json;

TEST(LodRequest, OptionsBecomeLodOptionsAndTheirCommandLine) {
  const LodRequest r = lod_request(json{{"method", "cluster"},
                                        {"error-range", 10},
                                        {"quality", {"polygon=3"}},
                                        {"ranges", {"sphere=5,10"}},
                                        {"join", true},
                                        {"no-lines", false}},
                                   "/data/my scene.wrl", "/data/out.wrl");
  EXPECT_EQ(r.options.method, SimplifyMethod::kCluster);
  EXPECT_FLOAT_EQ(r.options.range.error_range, 0.1f);
  EXPECT_EQ(r.options.manual.at("polygon").quality, 3);
  EXPECT_EQ(r.options.manual.at("sphere").ranges, (std::vector<float>{5, 10}));
  EXPECT_TRUE(r.options.join);
  EXPECT_FALSE(r.options.no_lines);
  EXPECT_EQ(r.command_line,
            "lodforge lod '/data/my scene.wrl' -o /data/out.wrl --error-range 10 --join "
            "--method cluster --quality polygon=3 --ranges sphere=5,10");
}

TEST(LodRequest, NoOptionsAreTheDefaults) {
  const LodRequest r = lod_request(json::object(), "a.wrl", "b.wrl");
  EXPECT_EQ(r.command_line, "lodforge lod a.wrl -o b.wrl");
  EXPECT_EQ(r.options.method, LodOptions{}.method);
  EXPECT_EQ(r.options.range.error_range, LodOptions{}.range.error_range);
  EXPECT_FALSE(r.options.camera_angle_given);
}

TEST(LodRequest, BadValuesNameTheOption) {
  const auto message = [](const json& o) {
    try {
      lod_request(o, "a.wrl", "b.wrl");
    } catch (const DataError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message({{"error-range", 0}}).find("error-range"), std::string::npos);
  EXPECT_NE(message({{"method", "fast"}}).find("fast"), std::string::npos);
  EXPECT_NE(message({{"quality", {"torus=2"}}}).find("torus"), std::string::npos);
  EXPECT_NE(message({{"ranges", {"5,3"}}}).find("increase"), std::string::npos);
  EXPECT_NE(message({{"join", 1}}).find("join"), std::string::npos);
  EXPECT_NE(message({{"output", "x"}}).find("unknown option 'output'"), std::string::npos);
  EXPECT_NE(message(json::array()).find("object"), std::string::npos);
}

}  // namespace
}  // namespace lodforge::studio
