// Where every command may write (issue 18, output paths): only regular files
// and new paths are replaced, through a temporary file and a rename; links
// stay links and their targets get the content; a file keeps its mode; device
// nodes, FIFOs, sockets and directories, the command's own inputs, one file
// written twice and two outputs on standard output are refused before
// anything is written (exit 1, a message naming the files); a failed write to
// standard output is exit 1 with a message. Device nodes are made in the
// test's folder (never the machine's /dev).
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "apps/run_command.h"
#include "core/special_files.h"
#include "lodforge/mesh/mesh_io.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::read_text;
using testing::run_lodforge;

// A command line writing one output, "{OUT}" where the output path goes.
struct Writer {
  std::string args;
  std::string extension;  ///< of the output
};

class OutputPathsCli : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    mesh_ = path("torus.obj");
    write_mesh(test::make_torus(1.0f, 0.35f, 16, 8), mesh_);
    scene_ = write("sphere.wrl", "#VRML V1.0 ascii\nSeparator { Sphere {} }\n");
  }
  // The torus's octree model, built on first use.
  const std::string& model() {
    if (model_.empty()) {
      model_ = path("torus.mco");
      auto r = run_lodforge("mco build " + mesh_ + " -o " + model_ + " --resolution 8");
      EXPECT_EQ(r.exit_code, 0) << r.err;
    }
    return model_;
  }
  // Every command that writes a file.
  std::vector<Writer> writers() {
    return {{"simplify " + mesh_ + " -o {OUT} --ratio 0.5", ".obj"},
            {"compare " + mesh_ + " " + mesh_ + " --samples 1000 --colored {OUT}", ".ply"},
            {"format " + scene_ + " -o {OUT}", ".wrl"},
            {"lod " + scene_ + " -o {OUT}", ".wrl"},
            {"lod " + scene_ + " -o " + path("good.wrl") + " --stats {OUT}", ".json"},
            {"render " + mesh_ + " -o {OUT} --size 16x16", ".png"},
            {"mco build " + mesh_ + " -o {OUT} --resolution 8", ".mco"},
            {"mco extract " + model() + " -o {OUT} --percent 50", ".obj"}};
  }
  static std::string with_output(std::string args, const std::string& out) {
    args.replace(args.find("{OUT}"), 5, out);
    return args;
  }
  // Names in the test's folder, to show that nothing was written.
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(dir_)) names.push_back(e.path());
    std::sort(names.begin(), names.end());
    return names;
  }
  static mode_t mode_of(const std::string& p) {
    struct stat st {};
    EXPECT_EQ(::stat(p.c_str(), &st), 0) << p;
    return st.st_mode & 07777;
  }
  std::string mesh_, scene_, model_;
};

TEST_F(OutputPathsCli, DevicesFifosSocketsAndDirectoriesAreRefusedBeforeWriting) {
  for (const Writer& w : writers()) {
    for (test::Special kind : test::kRefusedKinds) {
      const std::string node = path(std::string("node") + w.extension);
      if (!test::make_special(node, kind)) {
        // mknod needs privileges (the test runs have them as root); the other
        // kinds are still checked.
        ASSERT_EQ(kind, test::Special::kNullDevice) << "cannot make " << test::kind_text(kind);
        continue;
      }
      SCOPED_TRACE(with_output(w.args, node) + ": " + test::kind_text(kind));
      const auto before = listing();
      // A FIFO is refused without being opened: the command must not block.
      auto r = run_lodforge(with_output(w.args, node));
      EXPECT_EQ(r.exit_code, 1);
      EXPECT_THAT(r.err, HasSubstr("error: " + node + ": is " + test::kind_text(kind) +
                                   ", expected a regular file or a new path to write"));
      EXPECT_EQ(test::type_at(node), test::file_type_of(kind));
      EXPECT_EQ(listing(), before);  // lod --stats: not even the scene is written
      fs::remove(node);
    }
  }
}

TEST_F(OutputPathsCli, ScanFilesAreCheckedToo) {
  fs::create_directory(path("scans"));
  ASSERT_TRUE(test::make_special(path("scans/scan000.ply"), test::Special::kFifo));
  auto r = run_lodforge("mco scan " + mesh_ + " --views 2 --resolution 8 -o " + path("scans"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr(path("scans/scan000.ply") + ": is a FIFO"));
  EXPECT_EQ(test::type_at(path("scans/scan000.ply")), fs::file_type::fifo);
  EXPECT_FALSE(fs::exists(path("scans/scans.conf")));
}

TEST_F(OutputPathsCli, ALinkStaysALinkAndItsTargetGetsTheContentWithItsMode) {
  fs::create_directory(path("real"));
  for (const Writer& w : writers()) {
    const std::string target = path("real/target" + w.extension);
    const std::string link = path("link" + w.extension);
    std::ofstream(target) << "old";
    fs::permissions(target, fs::perms(0600));
    fs::create_symlink("real/target" + w.extension, link);
    SCOPED_TRACE(with_output(w.args, link));
    auto r = run_lodforge(with_output(w.args, link));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::is_symlink(link));
    EXPECT_NE(read_text(target), "old");
    EXPECT_GT(read_text(target).size(), 16u);
    EXPECT_EQ(mode_of(target), 0600u);
    // The temporary file was made beside the target, and renamed.
    for (const auto& e : fs::directory_iterator(path("real")))
      EXPECT_FALSE(e.path().filename().string().starts_with(".")) << e.path();
    fs::remove(link);
    fs::remove(target);
  }
}

TEST_F(OutputPathsCli, AnExistingFileKeepsItsModeANewOneGetsTheUmasks) {
  const std::string out = path("kept.obj");
  std::ofstream(out) << "old";
  fs::permissions(out, fs::perms(0600));
  auto r = run_lodforge("simplify " + mesh_ + " -o " + out + " --ratio 0.5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(mode_of(out), 0600u);
  EXPECT_GT(read_mesh(out).triangle_count(), 0u);
  const std::string fresh = path("fresh.obj");
  r = run_lodforge("simplify " + mesh_ + " -o " + fresh + " --ratio 0.5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const mode_t mask = ::umask(0);
  ::umask(mask);
  EXPECT_EQ(mode_of(fresh), 0666u & ~mask);
}

TEST_F(OutputPathsCli, AnOutputThatIsAnInputIsRefusedAndTheInputIsUnchanged) {
  const std::string cow = path("cow.obj");
  fs::copy_file(mesh_, cow);
  const std::string a = scene_;
  const std::string mesh_bytes = read_text(cow), scene_bytes = read_text(a);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"simplify " + cow + " -o " + cow + " --ratio 0.5",
       cow + ": the simplified mesh would overwrite the input " + cow},
      {"simplify " + cow + " -o " + path("./cow.obj") + " --ratio 0.5",
       path("./cow.obj") + ": the simplified mesh would overwrite the input " + cow},
      {"lod " + a + " -o " + a, a + ": the LOD scene of " + a + " would overwrite the input " + a},
      {"lod " + a + " --out-dir " + path("."),
       path("./sphere.wrl") + ": the LOD scene of " + a + " would overwrite the input " + a},
      {"lod " + a + " -o " + path("out.wrl") + " --stats " + a,
       a + ": the statistics (--stats) would overwrite the input " + a},
      {"compare " + cow + " " + mesh_ + " --colored " + cow,
       cow + ": the coloured mesh (--colored) would overwrite the input " + cow},
      {"format " + a + " -o " + a, a + ": the formatted scene would overwrite the input " + a},
      {"mco build " + cow + " -o " + cow, cow + ": the model would overwrite the input " + cow},
      {"render " + cow + " -o " + cow, cow + ": the picture would overwrite the input " + cow}};
  const auto before = listing();
  for (const auto& [args, message] : cases) {
    SCOPED_TRACE(args);
    auto r = run_lodforge(args);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, HasSubstr("error: " + message));
    EXPECT_EQ(read_text(cow), mesh_bytes);
    EXPECT_EQ(read_text(a), scene_bytes);
    EXPECT_EQ(listing(), before);
  }
}

TEST_F(OutputPathsCli, OutDirInputsOfTheSameNameAreRefusedBeforeWritingAnything) {
  const std::string one = write("d1/s.wrl", "#VRML V1.0 ascii\nSeparator { Sphere {} }\n");
  const std::string two = write("d2/s.wrl", "#VRML V1.0 ascii\nSeparator { Cube {} }\n");
  const std::string first = write("d0/first.wrl", "#VRML V1.0 ascii\nSeparator { Cone {} }\n");
  auto r = run_lodforge("lod " + first + " " + one + " " + two + " --out-dir " + path("dup"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("error: " + path("dup/s.wrl") + ": the LOD scene of " + one +
                               " and the LOD scene of " + two + " would both be written to it"));
  EXPECT_FALSE(fs::exists(path("dup")));  // not even first.wrl
}

TEST_F(OutputPathsCli, TwoOutputsOnStandardOutputAreRefused) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"lod " + scene_ + " -o - --stats -",
       "standard output: the LOD scene of " + scene_ +
           " and the statistics (--stats) would both be written to it"},
      {"simplify " + mesh_ + " -o - --format obj --ratio 0.5 --json",
       "standard output: the simplified mesh and the JSON summary (--json) would both be "
       "written to it"},
      {"compare " + mesh_ + " " + mesh_ + " --colored - --json",
       "standard output: the coloured mesh (--colored) and the JSON (--json) would both be "
       "written to it"}};
  for (const auto& [args, message] : cases) {
    SCOPED_TRACE(args);
    auto r = run_lodforge(args);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, HasSubstr("error: " + message));
    EXPECT_EQ(r.out, "");
  }
}

// Every command that writes standard output.
std::vector<std::string> stdout_writers(const std::string& mesh, const std::string& scene,
                                        const std::string& model, const std::string& out) {
  return {"info --json " + scene,
          "info " + scene,
          "simplify " + mesh + " -o " + out + " --ratio 0.5 --json",
          "simplify " + mesh + " -o - --format obj --ratio 0.5",
          "compare " + mesh + " " + mesh + " --samples 1000 --json",
          "mco info " + model + " --json",
          "format " + scene + " -o -",
          "lod " + scene + " -o -",
          "lod " + scene + " -o " + out + ".wrl --stats -",
          "render " + mesh + " -o - --size 16x16"};
}

TEST_F(OutputPathsCli, AFullStandardOutputIsExitOneWithAMessage) {
  const std::string full = path("full");
  if (!test::make_special(full, test::Special::kFullDevice))
    GTEST_SKIP() << "cannot make a device node here; the closed pipe test covers this";
  for (const std::string& args : stdout_writers(mesh_, scene_, model(), path("out.obj"))) {
    SCOPED_TRACE(args);
    auto r = run_lodforge(args, "", full);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, HasSubstr("error: "));  // lod names the scene between
    EXPECT_THAT(r.err, HasSubstr("cannot write to standard output: No space left"));
    EXPECT_EQ(test::type_at(full), fs::file_type::character);
  }
}

TEST_F(OutputPathsCli, AClosedPipeOnStandardOutputIsExitOneWithAMessage) {
  int ends[2];
  ASSERT_EQ(::pipe(ends), 0);
  ::close(ends[0]);  // nobody reads: every write fails with EPIPE
  // The shell redirects from a single-digit descriptor.
  const int fd = ::fcntl(ends[1], F_DUPFD, 3);
  ::close(ends[1]);
  ASSERT_GE(fd, 3);
  ASSERT_LE(fd, 9);
  for (const std::string& args : stdout_writers(mesh_, scene_, model(), path("out.obj"))) {
    SCOPED_TRACE(args);
    auto r = run_lodforge(args, "", "&" + std::to_string(fd));
    EXPECT_EQ(r.exit_code, 1);  // not killed by SIGPIPE
    EXPECT_THAT(r.err, HasSubstr("cannot write to standard output: Broken pipe"));
  }
  ::close(fd);
}

}  // namespace
}  // namespace lodforge
