#pragma once
// Runs the lodforge executable as a child process and captures what it says.
#include <sys/wait.h>

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/temp_dir.h"

namespace lodforge::testing {

struct CommandResult {
  int exit_code = -1;
  std::string out;  ///< standard output
  std::string err;  ///< standard error
};

inline std::string read_text(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

/// Runs `lodforge ARGS` through the shell (ARGS is shell text), with optional
/// standard input from a file. `stdout_to`, when given, is where standard
/// output goes instead of being captured, as shell redirection text: a path,
/// or "&N" for a descriptor the test process holds open.
inline CommandResult run_lodforge(const std::string& args, const std::string& stdin_file = "",
                                  const std::string& stdout_to = "") {
  namespace fs = std::filesystem;
  static int counter = 0;
  fs::path dir = fs::temp_directory_path() / ("lodforge_cli_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::string out = (dir / ("out" + std::to_string(counter))).string();
  std::string err = (dir / ("err" + std::to_string(counter++))).string();
  std::string cmd = std::string(LODFORGE_EXE) + " " + args + " >" +
                    (stdout_to.empty() ? out : stdout_to) + " 2>" + err;
  if (!stdin_file.empty())
    cmd += " <" + stdin_file;
  else
    cmd += " </dev/null";
  int status = std::system(cmd.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = read_text(out);
  r.err = read_text(err);
  fs::remove(out);
  fs::remove(err);
  std::error_code ignored;
  fs::remove(dir, ignored);  // only when empty: a run of each test leaves nothing
  return r;
}

/// Whether corpus-wide tests ask outside readers (Castle Model Viewer,
/// Coin3D) for their verdict. Under the sanitizers they do not: our code
/// writes the same bytes there (and is checked doing so), and the readers'
/// verdict on them is the Release run's.
#ifdef LODFORGE_SANITIZED
inline constexpr bool kOutsideReaders = false;
#else
inline constexpr bool kOutsideReaders = true;
#endif

/// Expects `r` to be a clean refusal of the input `in`: exit code 1, an
/// "error:" message, and no file written at `out`.
inline void expect_refused(const CommandResult& r, const std::string& in, const std::string& out) {
  EXPECT_EQ(r.exit_code, 1) << in << "\n" << r.err;
  EXPECT_NE(r.err.find("error:"), std::string::npos) << in;
  EXPECT_FALSE(std::filesystem::exists(out)) << in;
}

/// A test with a fresh folder of its own for input and output files.

}  // namespace lodforge::testing
