// The progress bar as a user sees it: drawn on a terminal (a pseudo-terminal
// made by util-linux `script`), never into a pipe, never with -q.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "apps/run_command.h"

namespace lodforge {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

class ProgressCli : public testing::TempDirTest {};

const std::string kScene = std::string(LODFORGE_EXAMPLES) + "/scene.wrl";  // lod: a few seconds
const std::string kBunny = std::string(LODFORGE_SHARED_DATA) + "/meshes/bun_zipper.ply";
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
       {"lod " + kScene + " -o " + path("scene.wrl"),
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
  const std::string shown = on_terminal("lod " + kScene + " -o " + path("scene.wrl"));
  // The bar: the file as its label, redrawn in place.
  EXPECT_THAT(shown, HasSubstr("\r" + kScene + ": shapes [")) << shown;
  EXPECT_THAT(shown, HasSubstr(" %")) << shown;
  // Cleared before the summary, which starts on a clean line.
  const auto summary = shown.find(kScene + ": 19 shapes");
  ASSERT_NE(summary, std::string::npos) << shown;
  const auto cleared = shown.rfind("\r\033[K", summary);
  ASSERT_NE(cleared, std::string::npos) << shown;
  const std::size_t after = cleared + 4;  // past "\r\033[K"
  EXPECT_EQ(shown.substr(after, summary - after).find('['), std::string::npos)
      << "nothing of the bar left before the summary";
}

TEST_F(ProgressCli, QuietDrawsNoBarOnATerminal) {
  if (!have_script()) GTEST_SKIP() << "util-linux `script` is not installed (no pseudo-terminal)";
  const std::string shown = on_terminal("lod " + kScene + " -o " + path("scene.wrl") + " -q");
  EXPECT_THAT(shown, Not(HasSubstr("shapes ["))) << shown;
  EXPECT_THAT(shown, HasSubstr(kScene + ": 19 shapes")) << "-q keeps the summary";
}

}  // namespace
}  // namespace lodforge
