#include "lodforge/apps/common_options.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <fmt/core.h>

namespace lodforge::apps {

const CLI::Validator kFiniteNumber(
    [](std::string& text) -> std::string {
      // Each comma-separated part of a list value, as a number if it is one.
      std::size_t start = 0;
      while (start <= text.size()) {
        const std::size_t end = std::min(text.find(',', start), text.size());
        const std::string part = text.substr(start, end - start);
        char* stop = nullptr;
        const double v = std::strtod(part.c_str(), &stop);
        if (!part.empty() && stop && *stop == '\0' && !std::isfinite(v))
          return fmt::format("'{}' is not a finite number", part);
        start = end + 1;
      }
      return {};
    },
    "FINITE");

void add_scene_read_options(CLI::App& cmd, SceneReadSettings& s) {
  cmd.add_flag("--inline", s.read_inlines,
               "Also read the local files of WWWInline nodes (never over a network)");
  cmd.add_flag("-q,--quiet", s.quiet, "Do not print warnings");
}

void add_writer_options(CLI::App& cmd, vrml1::WriteOptions& w) {
  cmd.add_option("--floats-per-line", w.floats_per_line, "Floats per line in lists")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  cmd.add_option("--ints-per-line", w.ints_per_line, "Integers per line in lists")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  cmd.add_flag("--no-tabs", w.no_tabs, "No indentation");
  cmd.add_flag("--minimize", w.minimize, "Smallest output: no indentation, no line breaks");
}

void print_diagnostic(const Diagnostic& d) {
  fmt::print(stderr, "{}: {}\n", to_string(d.level), d.text);
}

vrml1::ReadResult read_scene(const std::string& path, const SceneReadSettings& s) {
  vrml1::ReadOptions opt;
  opt.read_inlines = s.read_inlines;
  vrml1::ReadResult r = vrml1::read_vrml1_file(path, opt);
  if (!s.quiet)
    for (const auto& d : r.log.entries()) print_diagnostic(d);
  return r;
}

vrml1::ReadResult read_scene_data(std::string_view data, const std::string& path,
                                  const SceneReadSettings& s) {
  vrml1::ReadOptions opt;
  opt.read_inlines = s.read_inlines;
  opt.source_name = path == "-" ? "<stdin>" : path;
  if (path != "-") {
    const std::filesystem::path p(path);
    opt.base_dir = p.has_parent_path() ? p.parent_path().string() : ".";
  }
  vrml1::ReadResult r = vrml1::read_vrml1(data, opt);
  if (!s.quiet)
    for (const auto& d : r.log.entries()) print_diagnostic(d);
  return r;
}

}  // namespace lodforge::apps
