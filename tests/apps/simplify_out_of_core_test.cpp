// `lodforge simplify --method cluster` on a mesh larger than the memory the
// process may take: a bumpy torus of 2 M triangles (tests/tools/make_big_ply)
// under an address-space limit of 300 MB, which the in-memory path (about
// 600 MB for it) cannot run in and the streamed path can.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/run_command.h"
#include "core/temp_dir.h"
#include "lodforge/mesh/mesh_io.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using ::testing::HasSubstr;
using testing::read_text;
using testing::run_lodforge;

constexpr std::uint64_t kTriangles = 2000000;
constexpr int kLimitKiB = 300 * 1000;  // ulimit -v, in KiB

class SimplifyOutOfCore : public testing::TempDirTest {
 protected:
  /// The torus, written once per test.
  std::string torus() {
    const std::string p = path("torus.ply");
    const std::string cmd = std::string(LODFORGE_MAKE_BIG_PLY) + " " + p + " " +
                            std::to_string(kTriangles) + " >/dev/null";
    EXPECT_EQ(std::system(cmd.c_str()), 0);
    return p;
  }
  /// Runs `lodforge ARGS` under `ulimit -v kLimitKiB`.
  CommandResult run_limited(const std::string& args) {
    const std::string out = path("stdout"), err = path("stderr");
    const std::string cmd = "ulimit -v " + std::to_string(kLimitKiB) + " && exec " +
                            std::string(LODFORGE_EXE) + " " + args + " >" + out + " 2>" + err +
                            " </dev/null";
    const int status = std::system(("sh -c '" + cmd + "'").c_str());
    CommandResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = read_text(out);
    r.err = read_text(err);
    return r;
  }
};

TEST_F(SimplifyOutOfCore, StreamsUnderAMemoryLimitTheInMemoryPathExceeds) {
  const std::string in = torus();
  // The limit binds: the in-memory path (never streamed) runs out of memory.
  const std::string never = path("never.ply");
  CommandResult r = run_limited("simplify " + in + " -o " + never +
                                " --method cluster --ratio 0.01 --max-memory 0");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("out of memory"));
  EXPECT_FALSE(fs::exists(never));
  // The default budget follows the limit, so the same command streams.
  const std::string out = path("small.ply");
  r = run_limited("simplify " + in + " -o " + out + " --method cluster --ratio 0.01 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["out_of_core"].get<bool>());
  // make_big_ply rounds the count up to a whole grid of quads.
  const auto input = j["input_triangles"].get<std::uint64_t>();
  EXPECT_GE(input, kTriangles);
  EXPECT_LT(input, kTriangles + 4000);
  const auto target = j["target_triangles"].get<std::size_t>();
  EXPECT_EQ(target, input / 100);
  const auto got = j["output_triangles"].get<std::size_t>();
  EXPECT_LE(got, target);
  EXPECT_GE(double(got), 0.7 * double(target));
  EXPECT_THAT(j["error_kind"].get<std::string>(), HasSubstr("lodforge compare"));
  EXPECT_EQ(j["stop_reason"], "target reached");
  const TriangleMesh small = read_mesh(out);
  EXPECT_EQ(small.triangle_count(), got);
  // The torus has radii 1 and 0.4: the result keeps its extent.
  const Box3 box = small.bounds();
  EXPECT_NEAR(box.hi.x, 1.4, 0.1);
  EXPECT_NEAR(box.hi.z, 0.4, 0.05);
}

TEST_F(SimplifyOutOfCore, FlagForcesStreamingAndNeedsAStreamableClusterRun) {
  TriangleMesh tri;
  tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1}};
  tri.triangles = {{0, 1, 2}, {1, 3, 2}};
  write_mesh(tri, path("small.ply"));
  write_mesh(tri, path("small_ascii.ply"), {.binary = false});
  const std::string out = path("out.ply");
  CommandResult r = run_lodforge("simplify " + path("small.ply") + " -o " + out +
                                 " --method cluster --ratio 0.5 --out-of-core --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(nlohmann::json::parse(r.out)["out_of_core"].get<bool>());
  // Another method: a usage error.
  r = run_lodforge("simplify " + path("small.ply") + " -o " + out +
                   " --method qem --ratio 0.5 --out-of-core");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--method cluster only"));
  // A file it cannot stream: bad input, with the reason.
  fs::remove(out);
  r = run_lodforge("simplify " + path("small_ascii.ply") + " -o " + out +
                   " --method cluster --ratio 0.5 --out-of-core");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("small_ascii.ply: an ASCII PLY file"));
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace lodforge
