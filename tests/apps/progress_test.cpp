// The progress bar as a user sees it: drawn on a terminal (a pseudo-terminal
// made by util-linux `script`), never into a pipe, never with -q.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "apps/run_command.h"
#include "lod/lod_test_support.h"
#include "lodforge/mesh/mesh_io.h"

namespace lodforge {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

const std::string kBunny = std::string(LODFORGE_SHARED_DATA) + "/meshes/bun_zipper.ply";

class ProgressCli : public testing::TempDirTest {
 protected:
  // A scene of six bunnies, each its own IndexedFaceSet: `lod` on it takes
  // seconds, several times the bar's half-second delay (one bunny or the
  // example scene take about that delay itself).
  std::string bunny_scene() {
    const TriangleMesh m = read_mesh(kBunny);
    std::string text = "#VRML V1.0 ascii\nSeparator {\n";
    for (int copy = 0; copy < 6; ++copy) {
      const std::string one =
          testing::scene_of(m, fmt::format("Translation {{ translation {} 0 0 }}", copy * 0.2));
      text += one.substr(one.find('\n') + 1);  // its Separator, without the header
    }
    return write("bunnies.wrl", text + "}\n");
  }
};
const std::string kBunnyLow = std::string(LODFORGE_SHARED_DATA) + "/meshes/bun_zipper_res3.ply";

// Runs shell text and returns what it writes on stdout (read through a pipe).
std::string output_of(const std::string& command, int& exit_code) {
  std::FILE* p = popen(command.c_str(), "r");
  if (!p) return {};
  std::string out;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  const int status = pclose(p);
  exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

// `lodforge ARGS` with standard error into a pipe (standard output dropped):
// what the pipe received.
std::string stderr_through_pipe(const std::string& args) {
  int code = -1;
  std::string err = output_of(std::string(LODFORGE_EXE) + " " + args + " 2>&1 >/dev/null", code);
  EXPECT_EQ(code, 0) << args << "\n" << err;
  return err;
}

bool have_script() {
  return std::system("command -v script >/dev/null 2>&1") == 0;
}

// `lodforge ARGS` on a pseudo-terminal (util-linux `script`): what the
// terminal showed (standard output and standard error).
std::string on_terminal(const std::string& args) {
  int code = -1;
  std::string shown = output_of(
      "script -qfec '" + std::string(LODFORGE_EXE) + " " + args + "' /dev/null </dev/null", code);
  EXPECT_EQ(code, 0) << args << "\n" << shown;
  return shown;
}

TEST_F(ProgressCli, NoBarIntoAPipe) {
  // Each run takes over the bar's half second on this machine, so a bar
  // would be drawn if the pipe were taken for a terminal.
  for (const std::string& args :
       {"lod " + bunny_scene() + " -o " + path("scene.wrl"),
        "mco build " + kBunny + " -o " + path("bunny.mco") + " --resolution 250",
        "compare " + kBunny + " " + kBunnyLow + " --samples 2000000",
        "simplify " + kBunny + " -o " + path("low.ply") + " --ratio 0.1"}) {
    const std::string err = stderr_through_pipe(args);
    EXPECT_THAT(err, Not(HasSubstr("\r"))) << args;
    EXPECT_THAT(err, Not(HasSubstr("\033["))) << args;
  }
}

TEST_F(ProgressCli, LodDrawsABarOnATerminalAndClearsIt) {
  if (!have_script()) GTEST_SKIP() << "util-linux `script` is not installed (no pseudo-terminal)";
  const std::string scene = bunny_scene();
  const std::string shown = on_terminal("lod " + scene + " -o " + path("scene.wrl"));
  // The bar: the file as its label, redrawn in place.
  // (The label keeps its end when the line is short: "...bunnies.wrl".)
  EXPECT_THAT(shown, HasSubstr("bunnies.wrl: shapes [")) << shown;
  EXPECT_THAT(shown, HasSubstr("\r")) << shown;
  EXPECT_THAT(shown, HasSubstr(" %")) << shown;
  // Cleared before the summary, which starts on a clean line.
  const auto summary = shown.find(scene + ": 6 shapes");
  ASSERT_NE(summary, std::string::npos) << shown;
  const auto cleared = shown.rfind("\r\033[K", summary);
  ASSERT_NE(cleared, std::string::npos) << shown;
  const std::size_t after = cleared + 4;  // past "\r\033[K"
  // (Warnings may come between; they are not the bar.)
  EXPECT_EQ(shown.substr(after, summary - after).find("shapes ["), std::string::npos)
      << "nothing of the bar left before the summary";
}

TEST_F(ProgressCli, QuietDrawsNoBarOnATerminal) {
  if (!have_script()) GTEST_SKIP() << "util-linux `script` is not installed (no pseudo-terminal)";
  const std::string scene = bunny_scene();
  const std::string shown = on_terminal("lod " + scene + " -o " + path("scene.wrl") + " -q");
  EXPECT_THAT(shown, Not(HasSubstr("shapes ["))) << shown;
  EXPECT_THAT(shown, HasSubstr(scene + ": 6 shapes")) << "-q keeps the summary";
}

}  // namespace
}  // namespace lodforge
