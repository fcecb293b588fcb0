// The `lodforge` command: argv -> settings -> library calls. Exit codes:
// 0 success, 1 bad input (a message on stderr), 2 bad usage.
#include <fmt/core.h>

#include <CLI/CLI.hpp>
#include <exception>
#include <new>

#include "lodforge/apps/commands.h"
#include "lodforge/core/error.h"

int main(int argc, char** argv) {
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
    fmt::print(stderr, "internal error: {}\n", e.what());
    return 1;
  }
}
