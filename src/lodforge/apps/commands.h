#pragma once
/// The subcommands of the `lodforge` program. Each add_*_command registers its
/// options on the CLI11 app and, when selected, stores the function to run.
/// Runners return the exit code; bad input throws lodforge::DataError, which
/// main() reports and turns into exit code 1.
#include <CLI/CLI.hpp>
#include <functional>

namespace lodforge::apps {

using Runner = std::function<int()>;

void add_info_command(CLI::App& app, Runner& run);
void add_format_command(CLI::App& app, Runner& run);
void add_lod_command(CLI::App& app, Runner& run);
void add_render_command(CLI::App& app, Runner& run);
void add_compare_command(CLI::App& app, Runner& run);
void add_simplify_command(CLI::App& app, Runner& run);
void add_mco_command(CLI::App& app, Runner& run);
void add_report_command(CLI::App& app, Runner& run);
void add_studio_command(CLI::App& app, Runner& run);

}  // namespace lodforge::apps
