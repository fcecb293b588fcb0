// The `lodforge` command: argv -> settings -> library calls. Exit codes:
// 0 success, 1 bad input (a message on stderr), 2 bad usage.
#include <fmt/core.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <system_error>

#include "lodforge/apps/commands.h"
#include "lodforge/core/error.h"

namespace {

void print_stdout_error(const std::string& reason) {
  fmt::print(stderr, "error: cannot write to standard output{}{}\n", reason.empty() ? "" : ": ",
             reason);
}

// Runs the chosen command and turns what it throws into a message and an
// exit code.
int run_command(const lodforge::apps::Runner& run) {
  try {
    return run ? run() : 2;
  } catch (const CLI::Error& e) {  // a usage problem found after parsing
    fmt::print(stderr, "{}: {}\n", e.get_name(), e.what());
    return 2;
  } catch (const lodforge::DataError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "error: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    // fmt::print throws a system_error when a write to standard output fails.
    const auto* failed = dynamic_cast<const std::system_error*>(&e);
    if (failed && std::ferror(stdout))
      print_stdout_error(failed->code().message());
    else
      fmt::print(stderr, "internal error: {}\n", e.what());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  // A closed pipe on standard output is then a failed write, reported below
  // with exit code 1, rather than a silent death by signal.
  std::signal(SIGPIPE, SIG_IGN);
  using namespace lodforge::apps;
  CLI::App app{"lodforge: levels of detail for 3D scenes"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "lodforge 0.1.0");
  Runner run;
  add_info_command(app, run);
  add_format_command(app, run);
  add_lod_command(app, run);
  add_render_command(app, run);
  add_compare_command(app, run);
  add_simplify_command(app, run);
  add_mco_command(app, run);
  add_report_command(app, run);
  add_studio_command(app, run);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  const int code = run_command(run);
  // Every command's writes to standard output end here: what is still
  // buffered must reach it, and a write that failed unnoticed (a full disk, a
  // closed pipe) must not end in success.
  if (code != 0) return code;  // the failure is reported already
  errno = 0;
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    print_stdout_error(errno ? std::strerror(errno) : "");
    return 1;
  }
  return 0;
}
