#include "lodforge/apps/common_options.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string_view>
#include <utility>

#include <fmt/core.h>

#include "lodforge/core/error.h"
#include "lodforge/metrics/colorize_deviation.h"
#include "lodforge/render/color_bar.h"
#include "lodforge/scene/relocate_references.h"

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
  cmd.add_flag("-q{warnings},--quiet{warnings}", s.quiet_mode,
               "No warnings (the one-line summary stays); --quiet=all: nothing but errors")
      ->check(CLI::IsMember({"warnings", "all"}))
      ->each([&s](const std::string& v) {
        s.quiet = true;
        s.silent = s.silent || v == "all";
      });
  add_expansion_options(cmd, s);
}

void add_expansion_options(CLI::App& cmd, SceneReadSettings& s) {
  cmd.add_option("--max-instances", s.max_instances,
                 "Refuse a scene that expands to more node instances than this (each USE and "
                 "each inline repeats a subtree; 0 = no limit)")
      ->capture_default_str()
      ->check(kFiniteNumber)
      ->check(CLI::NonNegativeNumber);
  cmd.add_option("--max-triangles", s.max_triangles,
                 "Refuse a scene whose expanded shapes draw more triangles than this (estimated "
                 "while reading; 0 = no limit)")
      ->capture_default_str()
      ->check(kFiniteNumber)
      ->check(CLI::NonNegativeNumber);
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

namespace {

// "FILE:LINE: " or "FILE:LINE:COLUMN: " at the start of a message: its length
// and the location without the trailing ": " (0 and "" when there is none).
std::pair<std::size_t, std::string_view> location_prefix(std::string_view text) {
  for (std::size_t colon = text.find(':'); colon != std::string_view::npos;
       colon = text.find(':', colon + 1)) {
    std::size_t i = colon + 1, numbers = 0;
    while (numbers < 2 && i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) {
      while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i;
      ++numbers;
      if (i < text.size() && text[i] == ':' && i + 1 < text.size() &&
          std::isdigit(static_cast<unsigned char>(text[i + 1])))
        ++i;
      else
        break;
    }
    if (numbers > 0 && text.substr(i).starts_with(": ")) return {i + 2, text.substr(0, i)};
  }
  return {0, {}};
}

}  // namespace

void print_diagnostics(const std::vector<Diagnostic>& diagnostics) {
  struct Group {
    const Diagnostic* first;
    std::size_t count = 0;
  };
  std::vector<Group> groups;
  std::map<std::pair<LogLevel, std::string_view>, std::size_t> index;
  for (const Diagnostic& d : diagnostics) {
    const std::string_view message = std::string_view(d.text).substr(location_prefix(d.text).first);
    auto [it, fresh] = index.try_emplace({d.level, message}, groups.size());
    if (fresh) groups.push_back({&d});
    ++groups[it->second].count;
  }
  for (const Group& g : groups) {
    if (g.count == 1) {
      print_diagnostic(*g.first);
      continue;
    }
    const auto [length, where] = location_prefix(g.first->text);
    fmt::print(stderr, "{}: {} ({} times, first at {})\n", to_string(g.first->level),
               std::string_view(g.first->text).substr(length), g.count, where);
  }
}

namespace {

vrml1::ReadOptions read_options(const SceneReadSettings& s) {
  vrml1::ReadOptions opt;
  opt.read_inlines = s.read_inlines;
  opt.max_instances = s.max_instances;
  opt.max_triangles = s.max_triangles;
  return opt;
}

}  // namespace

vrml1::ReadResult read_scene(const std::string& path, const SceneReadSettings& s) {
  vrml1::ReadResult r = vrml1::read_vrml1_file(path, read_options(s));
  if (!s.quiet) print_diagnostics(r.log.entries());
  return r;
}

vrml1::ReadResult read_scene_data(std::string_view data, const std::string& path,
                                  const SceneReadSettings& s) {
  vrml1::ReadOptions opt = read_options(s);
  opt.source_name = path == "-" ? "<stdin>" : path;
  if (path != "-") {
    const std::filesystem::path p(path);
    opt.base_dir = p.has_parent_path() ? p.parent_path().string() : ".";
  }
  vrml1::ReadResult r = vrml1::read_vrml1(data, opt);
  if (!s.quiet) print_diagnostics(r.log.entries());
  return r;
}

Image add_deviation_bar(const Image& picture, double max) {
  return add_color_bar(picture, {.stops = {kDeviationScale.begin(), kDeviationScale.end()},
                                 .min = 0,
                                 .max = max,
                                 .title = "deviation"});
}

bool name_ends_with(std::string path, std::string_view suffix) {
  for (auto& c : path) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (path.ends_with(".gz")) path.resize(path.size() - 3);
  return path.ends_with(suffix);
}

void make_output_folder(const std::string& target) {
  namespace fs = std::filesystem;
  const fs::path to = target == "-" ? fs::path() : fs::path(target).parent_path();
  std::error_code ec;
  if (!to.empty() && (fs::create_directories(to, ec), ec))
    throw DataError(fmt::format("{}: cannot create the folder: {}", to.string(), ec.message()));
}

void relocate_to_output(scene::Scene& scene, const std::string& input, const std::string& output,
                        bool quiet) {
  namespace fs = std::filesystem;
  if (input == "-" || output == "-") return;
  const fs::path to = fs::path(output).parent_path();
  const auto moved = scene::relocate_references(scene, fs::path(input).parent_path(), to);
  if (moved.rewritten && !quiet)
    fmt::print(stderr, "{}: {} file reference{} made relative to {}\n", input, moved.rewritten,
               moved.rewritten == 1 ? "" : "s", to.empty() ? "." : to.string());
}

}  // namespace lodforge::apps
