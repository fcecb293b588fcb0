// Batches of `lodforge lod`: manifests, shards, reports and their merge, and
// the two ways the README gives to run shards (GNU parallel, Slurm).
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/run_command.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using ::testing::HasSubstr;
using testing::read_text;
using testing::run_lodforge;

/// A batch of small real scenes: copies of corpus files in a folder tree,
/// listed by a manifest with relative paths, plus one missing file.
class Batch : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    std::vector<fs::path> found;
    for (const auto& e : fs::recursive_directory_iterator(fs::path(LODFORGE_SHARED_DATA) / "vrml1"))
      if (e.is_regular_file() && e.path().extension() == ".wrl" && e.file_size() < 40'000)
        found.push_back(e.path());
    std::sort(found.begin(), found.end());
    ASSERT_GE(found.size(), 9u);
    std::string manifest = "# a small library\n\n";
    for (std::size_t i = 0; i < 9; ++i) {
      const std::string rel = fmt::format("set{}/{}_{}", i % 3, i, found[i].filename().string());
      fs::create_directories(fs::path(path("lib/" + rel)).parent_path());
      fs::copy_file(found[i], path("lib/" + rel));
      manifest += rel + "\n";
    }
    manifest += "  set0/missing.wrl  \n";  // blanks are trimmed; the file is not there
    write("lib/manifest.txt", manifest);
  }
  std::string lod_args(const std::string& out, const std::string& more) {
    return "lod --manifest " + path("lib/manifest.txt") + " --out-dir " + path(out) + " -q " + more;
  }
  /// A report without what differs between runs: times, the output folder.
  static nlohmann::json comparable(nlohmann::json r, const std::string& out_dir) {
    for (auto& f : r["files"]) {
      f.erase("seconds");
      std::string o = f["output"];
      f["output"] = o.substr(o.find(out_dir) + out_dir.size());
    }
    r["totals"].erase("seconds");
    return r;
  }
};

TEST_F(Batch, FourShardsThroughGnuParallelEqualOneProcess) {
  // One process.
  CommandResult one = run_lodforge(lod_args("one", "--report " + path("one.json")));
  EXPECT_EQ(one.exit_code, 1) << "the missing file fails the batch";
  EXPECT_THAT(one.err, HasSubstr("missing.wrl"));
  // Four shards, two at a time, through GNU parallel as the README shows.
  const std::string cmd =
      fmt::format("seq 0 3 | parallel -j2 '{} {}' >/dev/null 2>&1", LODFORGE_EXE,
                  lod_args("sharded", "--shard {}/4 --report " + path("r{}.json")));
  std::system(cmd.c_str());
  std::vector<std::string> reports;
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(fs::exists(path(fmt::format("r{}.json", i)))) << "shard " << i;
    reports.push_back(path(fmt::format("r{}.json", i)));
  }
  CommandResult merged = run_lodforge("report " + reports[2] + " " + reports[0] + " " + reports[3] +
                                      " " + reports[1] + " -o " + path("all.json"));
  EXPECT_EQ(merged.exit_code, 1) << merged.err;  // one scene failed
  EXPECT_THAT(merged.out, HasSubstr("batch of 10 scenes in 4 shards: 9 written, 1 failed"));
  EXPECT_THAT(merged.out, HasSubstr("failed: "));
  // The same scenes written, byte for byte, under the library's own tree.
  std::size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(path("one"))) {
    if (!e.is_regular_file()) continue;
    ++files;
    const fs::path rel = fs::relative(e.path(), path("one"));
    EXPECT_TRUE(rel.string().starts_with("set")) << rel;
    EXPECT_EQ(read_text(e.path().string()), read_text((fs::path(path("sharded")) / rel).string()))
        << rel;
  }
  EXPECT_EQ(files, 9u);
  // The merged report is the one-process report (times aside).
  const auto a = comparable(nlohmann::json::parse(read_text(path("one.json"))), "one");
  const auto b = comparable(nlohmann::json::parse(read_text(path("all.json"))), "sharded");
  EXPECT_EQ(a, b);
  EXPECT_EQ(a["totals"]["written"], 9);
  EXPECT_EQ(a["files"][9]["status"], "failed");
}

TEST_F(Batch, ShardsSplitRoundRobinAndMergeChecksThem) {
  ASSERT_EQ(run_lodforge(lod_args("s", "--shard 1/3 --report " + path("r1.json"))).exit_code, 0);
  const auto r1 = nlohmann::json::parse(read_text(path("r1.json")));
  std::vector<std::size_t> indices;
  for (const auto& f : r1["files"]) indices.push_back(f["index"]);
  EXPECT_EQ(indices, (std::vector<std::size_t>{1, 4, 7}));
  // Shards missing, twice the same, of another batch: refused with the reason.
  CommandResult missing = run_lodforge("report " + path("r1.json"));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_THAT(missing.err, HasSubstr("shards missing: 0/3, 2/3"));
  fs::copy_file(path("r1.json"), path("again.json"));
  CommandResult twice = run_lodforge("report " + path("r1.json") + " " + path("again.json"));
  EXPECT_EQ(twice.exit_code, 1);
  EXPECT_THAT(twice.err, HasSubstr("both are shard 1/3"));
  // Shard 0 of 2 (indices 0, 2, ..., 8) does not hold the missing file (9).
  ASSERT_EQ(run_lodforge(lod_args("t", "--shard 0/2 --report " + path("other.json"))).exit_code, 0);
  CommandResult other = run_lodforge("report " + path("r1.json") + " " + path("other.json"));
  EXPECT_EQ(other.exit_code, 1);
  EXPECT_THAT(other.err, HasSubstr("is of another batch"));
  // A report with a field of the wrong kind is named, not an internal error.
  auto broken = nlohmann::json::parse(read_text(path("r1.json")));
  broken["files"][0]["triangles"] = "many";
  write("broken.json", broken.dump());
  CommandResult incomplete = run_lodforge("report " + path("broken.json"));
  EXPECT_EQ(incomplete.exit_code, 1);
  EXPECT_THAT(incomplete.err, HasSubstr("broken.json: not a complete batch report"));
  CommandResult junk = run_lodforge("report " + path("lib/manifest.txt"));
  EXPECT_EQ(junk.exit_code, 1);
  EXPECT_THAT(junk.err, HasSubstr("not JSON"));
}

TEST_F(Batch, BadShardsAndMissingOutDirAreUsageErrors) {
  for (const char* bad : {"4/4", "1", "a/b", "1/0", "-1/3"}) {
    CommandResult r = run_lodforge(lod_args("x", std::string("--shard ") + bad));
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_THAT(r.err, HasSubstr("--shard")) << bad;
  }
  CommandResult r = run_lodforge("lod --manifest " + path("lib/manifest.txt") + " -q");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--out-dir"));
  CommandResult none = run_lodforge("lod --out-dir " + path("x"));
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_THAT(none.err, HasSubstr("--manifest"));
}

TEST_F(Batch, AManifestCannotNameStandardInputOrBeMissing) {
  write("bad.txt", "a.wrl\n-\n");
  CommandResult r = run_lodforge("lod --manifest " + path("bad.txt") + " --out-dir " + path("o"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("bad.txt:2: a manifest cannot name standard input"));
  CommandResult gone =
      run_lodforge("lod --manifest " + path("none.txt") + " --out-dir " + path("o"));
  EXPECT_EQ(gone.exit_code, 1);
  EXPECT_THAT(gone.err, HasSubstr("none.txt"));
}

TEST(SlurmExample, IsValidShell) {
  const std::string script = std::string(LODFORGE_EXAMPLES) + "/slurm_lod_batch.sh";
  ASSERT_TRUE(fs::exists(script));
  EXPECT_EQ(std::system(("bash -n " + script).c_str()), 0);
  EXPECT_THAT(read_text(script), HasSubstr("--shard \"$SLURM_ARRAY_TASK_ID/"));
}

}  // namespace
}  // namespace lodforge

namespace lodforge {
namespace {

TEST_F(Batch, OutputsThatCollideAreRefusedByEveryShard) {
  // Two absolute paths of one file name land on one output: every shard
  // refuses the batch before writing, including the shard holding one.
  write("lib/a/x.wrl", "#VRML V1.0 ascii\nSeparator {}\n");
  write("lib/b/x.wrl", "#VRML V1.0 ascii\nSeparator {}\n");
  write("clash.txt", path("lib/a/x.wrl") + "\n" + path("lib/b/x.wrl") + "\n");
  for (const char* shard : {"0/2", "1/2"}) {
    CommandResult r = run_lodforge("lod --manifest " + path("clash.txt") + " --out-dir " +
                                   path("o") + " --shard " + shard);
    EXPECT_EQ(r.exit_code, 1) << shard;
    EXPECT_THAT(r.err, HasSubstr("would both be written to it")) << shard;
    EXPECT_FALSE(fs::exists(path("o/x.wrl"))) << shard;
  }
}

}  // namespace
}  // namespace lodforge
