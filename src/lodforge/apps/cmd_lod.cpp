// `lodforge lod SCENE... -o OUT | --out-dir DIR [options]`: the main job —
// every shape of a VRML 1.0 scene becomes an LOD node.
#include <fmt/core.h>
#include <fmt/ranges.h>
#include <tbb/global_control.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

#include "lodforge/apps/batch.h"
#include "lodforge/apps/commands.h"
#include "lodforge/apps/common_options.h"
#include "lodforge/apps/lod_gltf.h"
#include "lodforge/apps/lod_vrml97.h"
#include "lodforge/apps/write_scene_gltf.h"
#include "lodforge/apps/write_scene_vrml97.h"
#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/core/output_path.h"
#include "lodforge/core/progress.h"
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/lod/generate_lod.h"
#include "lodforge/scene/relocate_references.h"

namespace lodforge::apps {
namespace {

const std::vector<std::string> kTypes = {"polygon", "line", "sphere", "cone", "cylinder", "cube"};

std::vector<float> parse_floats(const std::string& text, const std::string& what) {
  std::vector<float> v;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t comma = text.find(',', pos);
    std::string part =
        text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    try {
      std::size_t used = 0;
      float f = std::stof(part, &used);
      if (used != part.size() || !(f > 0)) throw std::invalid_argument(part);
      v.push_back(f);
    } catch (const std::exception&) {
      throw CLI::ValidationError(
          what, "expected positive numbers separated by commas, got '" + part + "'");
    }
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  for (std::size_t i = 1; i < v.size(); ++i)
    if (v[i] <= v[i - 1]) throw CLI::ValidationError(what, "ranges must increase");
  return v;
}

// "TYPE=value" -> the type (checked) and the value.
std::pair<std::string, std::string> split_typed(const std::string& text, const std::string& what) {
  auto eq = text.find('=');
  if (eq == std::string::npos) return {"", text};
  std::string type = text.substr(0, eq);
  if (std::find(kTypes.begin(), kTypes.end(), type) == kTypes.end())
    throw CLI::ValidationError(
        what, "unknown shape type '" + type + "' (polygon, line, sphere, cone, cylinder, cube)");
  return {type, text.substr(eq + 1)};
}

struct Settings {
  std::vector<std::string> inputs;
  std::string output, out_dir, stats, manifest, shard_text, report;
  Shard shard;
  std::string method = "qem", export_flavour = "spec";
  std::string format;  ///< --format: VRML97 / X3D output encoding, or glTF container
  double error_range_pct = 2, min_diff_pct = 20, level_spacing = kDefaultLevelSpacing,
         level_ratio = kDefaultLevelRatio;
  double camera_angle = -1, quad_split_angle = 0.174533;
  int levels = 0, threads = 0;
  std::optional<int> extract;
  std::vector<std::string> quality, ranges, verbose;
  bool join = false, no_lines = false, no_quads = false, by_size = false;
  SceneReadSettings read;
  vrml1::WriteOptions write;
};

LodOptions lod_options(const Settings& s) {
  LodOptions o;
  o.method = s.method == "cluster"    ? SimplifyMethod::kCluster
             : s.method == "decimate" ? SimplifyMethod::kDecimate
                                      : SimplifyMethod::kQem;
  o.range.error_range = float(s.error_range_pct / 100.0);
  if (s.camera_angle > 0) {
    o.range.camera_angle = float(s.camera_angle);
    o.camera_angle_given = true;
  }
  o.min_diff = float(s.min_diff_pct / 100.0);
  o.level_spacing = s.level_spacing;
  o.level_ratio = s.level_ratio;
  o.max_levels = std::size_t(s.levels);
  o.differentiate_by_size = s.by_size;
  o.no_lines = s.no_lines;
  o.join = s.join;
  o.triangulation.quad_split_angle = float(s.quad_split_angle);
  o.triangulation.keep_quads = !s.no_quads;
  o.export_flavour = s.export_flavour == "performer" ? ExportFlavour::kPerformer
                     : s.export_flavour == "reducer" ? ExportFlavour::kReducer
                                                     : ExportFlavour::kSpec;
  o.extract = s.extract;
  o.threads = s.threads;
  for (const auto& q : s.quality) {
    auto [type, value] = split_typed(q, "--quality");
    int n = -1;
    try {
      n = std::stoi(value);
    } catch (const std::exception&) {
    }
    if (type.empty() || n < 0)
      throw CLI::ValidationError("--quality", "expected TYPE=N with N >= 0, got '" + q + "'");
    o.manual[type].quality = n;
  }
  for (const auto& r : s.ranges) {
    auto [type, value] = split_typed(r, "--ranges");
    std::vector<float> v = parse_floats(value, "--ranges");
    if (type.empty())
      for (const auto& t : kTypes) o.manual[t].ranges = v;
    else
      o.manual[type].ranges = v;
  }
  return o;
}

nlohmann::ordered_json stats_json(const std::string& file, const LodResult& r) {
  nlohmann::ordered_json j;
  j["file"] = file;
  j["camera_angle"] = r.camera_angle;
  std::size_t original = 0;
  for (const auto& s : r.shapes) {
    nlohmann::ordered_json sj;
    sj["type"] = s.type;
    if (!s.name.empty()) sj["name"] = s.name;
    sj["line"] = s.line;
    sj["occurrences"] = s.occurrences;
    sj["method"] = s.method;
    sj["radius"] = s.radius;
    sj["scale"] = s.scale;
    for (const auto& l : s.levels)
      sj["levels"].push_back(
          {{"triangles", l.triangles}, {"vertices", l.vertices}, {"error", l.error}});
    sj["ranges"] = s.ranges;
    if (!s.stop_reason.empty()) sj["stop_reason"] = s.stop_reason;
    if (!s.levels.empty()) original += s.levels[0].triangles * s.occurrences;
    j["shapes"].push_back(sj);
  }
  j["triangles"] = original;
  for (const auto& [d, t] : r.triangles_by_distance)
    j["triangles_by_distance"].push_back({{"distance", d}, {"triangles", t}});
  return j;
}

// Where the LOD scene of `item` goes: -o, or --out-dir/<its output name>
// (a compressed input gives a compressed output).
std::string output_of(const BatchItem& item, const Settings& s) {
  if (s.out_dir.empty()) return s.output;
  return (std::filesystem::path(s.out_dir) / item.output_name).string();
}

// Refuses, before any scene is read, outputs that would replace an input,
// land on one file twice (--out-dir and inputs of the same name) or share
// standard output.
void check_outputs(const Settings& s, const std::vector<BatchItem>& items) {
  std::vector<OutputPath> outputs;
  std::vector<std::string> inputs;
  for (const auto& item : items) {
    outputs.push_back(
        {output_of(item, s),
         fmt::format("the LOD scene of {}", item.input == "-" ? "standard input" : item.input)});
    inputs.push_back(item.input);
  }
  if (!s.stats.empty()) outputs.push_back({s.stats, "the statistics (--stats)"});
  if (!s.report.empty()) outputs.push_back({s.report, "the batch report (--report)"});
  if (!s.manifest.empty()) inputs.push_back(s.manifest);
  check_output_paths(outputs, inputs);
}

// One line, and the triangles-by-distance table when `table`.
void print_summary(const std::string& file, const LodResult& r, bool table) {
  std::size_t levels = 0, lods = 0;
  for (const auto& s : r.shapes) {
    if (s.ranges.empty()) continue;
    ++lods;
    levels += s.levels.size() + 1;
  }
  fmt::print(stderr, "{}: {} shapes, {} with LOD ({} levels in all), camera angle {:.4g} rad\n",
             file, r.shapes.size(), lods, levels, r.camera_angle);
  if (!table || r.triangles_by_distance.empty()) return;
  fmt::print(stderr, "  distance      triangles drawn\n");
  for (const auto& [d, t] : r.triangles_by_distance)
    fmt::print(stderr, "  {:>10.4g}  {:>12}\n", d, t);
}

std::size_t file_size_or_zero(const std::string& path) {
  std::error_code ec;
  const auto size = path == "-" ? 0 : std::filesystem::file_size(path, ec);
  return ec ? 0 : static_cast<std::size_t>(size);
}

// A warning naming the options given that only the VRML 1.0 / Inventor
// pipeline uses, for a VRML97 / X3D or (`gltf`) glTF scene.
void warn_unused_options(const Settings& s, bool gltf, Log& log) {
  std::vector<std::string> unused;
  if (s.join) unused.push_back("--join");
  if (s.no_lines) unused.push_back("--no-lines");
  if (s.export_flavour != "spec") unused.push_back("--export");
  if (unused.empty()) return;
  log.warn(LogCategory::kGeneral,
           fmt::format("{} {} not used for a {} scene", fmt::join(unused, ", "),
                       unused.size() == 1 ? "is" : "are", gltf ? "glTF" : "VRML97 / X3D"));
}

// Reads one scene, makes its LODs and writes them; a DataError is the
// outcome's error. `progress` receives the library's progress, drawn on
// `bar`, which is cleared before anything is printed; `stats` gets the
// scene's statistics when it is written.
BatchOutcome lod_one(const BatchItem& item, const Settings& s, const LodOptions& options,
                     const std::vector<LogCategory>& shown, Progress& bar,
                     const ProgressCallback& progress, nlohmann::ordered_json& stats) {
  namespace fs = std::filesystem;
  const auto start = std::chrono::steady_clock::now();
  const std::string& input = item.input;
  BatchOutcome out{.index = item.index, .input = input, .output = output_of(item, s)};
  out.bytes_in = file_size_or_zero(input);
  try {
    LodOptions drawn = options;
    drawn.progress = progress;
    // A glTF scene written as VRML97 / X3D goes the VRML97 way.
    const bool gltf_in = is_gltf_input(input);
    const bool gltf = gltf_in && !writes_vrml97_family(out.output, s.format);
    const bool vrml97 = gltf_in ? !gltf : is_vrml97_input(input);
    const bool as_gltf = s.format == "gltf" || s.format == "glb" ||
                         (s.format.empty() && gltf::is_gltf_path(out.output));
    // A VRML 1.0 / Inventor scene may be written as VRML97 or X3D classic.
    const std::string as_vrml97 =
        !vrml97 && !gltf && !as_gltf ? vrml97_format_of(s.format, out.output) : "";
    if (gltf || vrml97) make_output_folder(out.output);
    LodResult result =
        gltf     ? lod_gltf_file(input, out.output, s.format, drawn)
        : vrml97 ? lod_vrml97_file(input, out.output, s.format, drawn, s.read.quiet, s.write)
                 : LodResult{};
    if (vrml97 || gltf) warn_unused_options(s, gltf, result.log);
    if (!vrml97 && !gltf) {
      SceneReadSettings read = s.read;
      read.quiet = true;  // the reader's warnings are printed here, off the bar
      vrml1::ReadResult r = read_scene(input, read);
      if (!s.read.quiet && !r.log.entries().empty()) {
        bar.clear();
        print_diagnostics(r.log.entries());
      }
      result = generate_lod(std::move(r.scene), drawn);
    }
    warn_unused_writer_options(s.write, input, out.output, s.format, result.log);
    bar.clear();
    if (!s.read.quiet) {
      std::vector<Diagnostic> show;
      for (const auto& d : result.log.entries())
        if (d.level != LogLevel::kMessage ||
            std::find(shown.begin(), shown.end(), d.category) != shown.end())
          show.push_back(d);
      print_diagnostics(show);
    }
    const std::string& target = out.output;
    const fs::path to = target == "-" ? fs::path() : fs::path(target).parent_path();
    make_output_folder(target);
    if (!vrml97 && !gltf) relocate_to_output(result.scene, input, target, s.read.quiet);
    if (!vrml97 && !gltf) {
      // A VRML 1.0 / Inventor scene is written as glTF when asked (--format
      // or an output named .glb / .gltf), else in its own language.
      if (as_gltf)
        write_scene_gltf(result.scene, target, to.string(), result.camera_angle,
                         s.format.empty() ? gltf_binary_name(target) : s.format == "glb",
                         s.read.quiet);
      else if (!as_vrml97.empty())
        write_scene_vrml97(result.scene, target, as_vrml97, s.read.quiet, s.write);
      else
        vrml1::write_vrml1_file(result.scene, target, s.write);
    }
    if (!s.read.silent) print_summary(input, result, !s.read.quiet);
    stats = stats_json(input, result);
    out.written = true;
    out.bytes_out = file_size_or_zero(target);
    out.shapes = result.shapes.size();
    for (const auto& shape : result.shapes) {
      if (shape.ranges.empty()) continue;
      ++out.shapes_with_lod;
      out.levels += shape.levels.size() + 1;
    }
    out.triangles = stats["triangles"].get<std::size_t>();
  } catch (const DataError& e) {
    bar.clear();
    fmt::print(stderr, "error: {}{}\n",
               std::string(e.what()).starts_with(input) ? "" : input + ": ", e.what());
    out.error = e.what();
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

// The scenes of the whole batch: the manifest's, then the command line's.
std::vector<BatchItem> batch_items(const Settings& s) {
  std::vector<BatchItem> items;
  if (!s.manifest.empty()) items = read_manifest(s.manifest);
  for (auto& item : command_line_items(s.inputs, items.size())) items.push_back(std::move(item));
  return items;
}

int run_lod(const Settings& s) {
  // --threads bounds the whole command (reading and writing too), not only
  // the level making.
  std::optional<tbb::global_control> thread_limit;
  if (s.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism,
                         static_cast<std::size_t>(s.threads));
  if (s.inputs.empty() && s.manifest.empty())
    throw CLI::ValidationError("SCENE", "give the scenes (or --manifest FILE)");
  const bool batch = s.inputs.size() > 1 || !s.manifest.empty() || s.shard.count > 1;
  if (batch && s.out_dir.empty())
    throw CLI::ValidationError("--out-dir", "several scenes, a manifest or a shard need --out-dir");
  if (!batch && s.output.empty() && s.out_dir.empty())
    throw CLI::ValidationError("-o", "give -o OUT (or --out-dir DIR)");
  std::vector<LogCategory> shown;
  for (const auto& v : s.verbose) {
    LogCategory c;
    if (!parse_category(v, c))
      throw CLI::ValidationError("--verbose", "unknown category '" + v + "'");
    shown.push_back(c);
  }
  const LodOptions options = lod_options(s);
  // The outputs of the whole batch are checked, so that every shard refuses
  // a batch whose outputs collide, not only the shards holding both.
  const std::vector<BatchItem> all = batch_items(s);
  check_outputs(s, all);
  const std::vector<BatchItem> items = select_shard(all, s.shard);
  const std::size_t batch_size = all.size();
  // One bar: a scene's own, or the batch's by input bytes (with the time left).
  std::size_t total_bytes = 0, done_bytes = 0;
  for (const auto& item : items) total_bytes += file_size_or_zero(item.input);
  std::optional<Progress> batch_bar;
  if (items.size() > 1)
    batch_bar.emplace(fmt::format("lod of {} scenes", items.size()), total_bytes,
                      stderr_progress(s.read.quiet));
  std::vector<BatchOutcome> outcomes;
  nlohmann::ordered_json all_stats = nlohmann::ordered_json::array();
  for (const auto& item : items) {
    const std::size_t size = file_size_or_zero(item.input);
    std::optional<Progress> scene_bar;
    ProgressCallback progress;
    if (batch_bar) {
      progress = [&, size](std::string_view, std::uint64_t done, std::uint64_t total) {
        batch_bar->update(done_bytes + (total ? size * done / total : 0));
      };
    } else {
      scene_bar.emplace(item.input == "-" ? "stdin" : item.input, 0, stderr_progress(s.read.quiet));
      progress = scene_bar->callback();
    }
    nlohmann::ordered_json stats;
    outcomes.push_back(
        lod_one(item, s, options, shown, batch_bar ? *batch_bar : *scene_bar, progress, stats));
    if (outcomes.back().written) all_stats.push_back(std::move(stats));
    done_bytes += size;
    if (batch_bar) batch_bar->update(done_bytes);
  }
  if (batch_bar) batch_bar->finish();
  // Statistics of the scenes that were written; none when none was.
  if (!s.stats.empty() && !all_stats.empty()) {
    std::string text = (all_stats.size() == 1 ? all_stats[0] : all_stats).dump(2) + "\n";
    write_file_atomic(s.stats, text);
  }
  if (!s.report.empty())
    write_file_atomic(s.report,
                      batch_report(s.manifest, batch_size, s.shard, outcomes).dump(2) + "\n");
  const bool failed =
      std::any_of(outcomes.begin(), outcomes.end(), [](const auto& o) { return !o.written; });
  return failed ? 1 : 0;
}

}  // namespace

void add_lod_command(CLI::App& app, Runner& run) {
  auto s = std::make_shared<Settings>();
  CLI::App* cmd = app.add_subcommand(
      "lod",
      "Replace every shape of scenes (VRML 1.0, Inventor, VRML97, X3D classic, glTF) by LOD nodes");
  cmd->add_option("SCENE", s->inputs,
                  "VRML 1.0 or Inventor files (- = stdin); Inventor is written as Inventor 2.1");
  auto* out = cmd->add_option("-o,--output", s->output,
                              "Output file (- = stdout; .gz: gzip-compressed), for one scene");
  auto* dir = cmd->add_option(
      "--out-dir", s->out_dir,
      "Output folder, for several scenes or a manifest; each keeps its input's name, or the "
      "manifest's relative path (x.wrl.gz stays compressed)");
  out->excludes(dir);
  cmd->add_option("--manifest", s->manifest,
                  "Batch: a file listing scenes, one path per line (relative to its folder; "
                  "# comments); outputs mirror the listed relative paths under --out-dir");
  cmd->add_option("--shard", s->shard_text,
                  "Batch: process only shard I of N (I/N, from 0): the scenes whose place in the "
                  "list is I modulo N")
      ->check([s](const std::string& text) {
        try {
          s->shard = parse_shard(text);
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
        return std::string();
      });
  cmd->add_option("--report", s->report,
                  "Write the batch report (JSON: every scene's outcome, sizes, triangles, time) "
                  "to this file; `lodforge report` merges the reports of shards");
  cmd->add_option("--format", s->format,
                  "Output encoding of a VRML97 / X3D scene: vrml97, x3dv or x3d (default: from "
                  "the output name, .x3dv X3D classic, .x3d X3D XML, else the input's), or of a "
                  "glTF scene: gltf, glb, or vrml97, x3dv or x3d (made a VRML97 scene first) "
                  "(default: from the output name, .wrl VRML97, else the input's); a VRML 1.0 / "
                  "Inventor scene is "
                  "converted to vrml97, x3dv, x3d, gltf or glb (default: from the output name, "
                  ".x3dv, .x3d, .glb, .gltf, else VRML 1.0)")
      ->check(CLI::IsMember({"vrml97", "x3dv", "x3d", "gltf", "glb"}));
  cmd->add_option("--method", s->method, "Simplifier: cluster, decimate or qem")
      ->capture_default_str()
      ->check(CLI::IsMember({"cluster", "decimate", "qem"}));
  cmd->add_option("--error-range", s->error_range_pct, "Allowed error in % of the screen height")
      ->capture_default_str()
      ->check(kFiniteNumber)
      ->check(CLI::Range(0.0001, 100.0));
  cmd->add_option("--camera-angle", s->camera_angle,
                  "Camera height angle in radians (default: first PerspectiveCamera, else pi/4)")
      ->check(kFiniteNumber)
      ->check(CLI::Range(0.0001, 3.14));
  cmd->add_option("--min-diff", s->min_diff_pct,
                  "Candidate levels: each keeps at most (100 - PCT) % of the previous")
      ->capture_default_str()
      ->check(kFiniteNumber)
      ->check(CLI::Range(1.0, 100.0));
  cmd->add_option("--level-spacing", s->level_spacing,
                  "Automatic mode: keep a level only where it is shown over at least this "
                  "factor of distance (1 keeps every candidate)")
      ->capture_default_str()
      ->check(kFiniteNumber)
      ->check(CLI::Range(1.0, 100.0));
  cmd->add_option("--level-ratio", s->level_ratio,
                  "Automatic mode: a level keeps at most this fraction of the triangles of the "
                  "level before it (1: no size rule)")
      ->capture_default_str()
      ->check(kFiniteNumber)
      ->check(CLI::Range(0.01, 1.0));
  cmd->add_option("--levels", s->levels, "At most N levels per shape (original and empty included)")
      ->check(kFiniteNumber)
      ->check(CLI::Range(2, 1000));
  cmd->add_option("--quality", s->quality,
                  "Manual mode per shape type: TYPE=N (0 empty, 1 no LOD, N levels); types "
                  "polygon, line, sphere, cone, cylinder, cube")
      ->delimiter(' ');
  cmd->add_option("--ranges", s->ranges, "Explicit LOD ranges: a,b,... or TYPE=a,b,...");
  cmd->add_flag("--differentiate-by-size", s->by_size,
                "Fewer levels for smaller objects (manual mode)");
  cmd->add_flag("--join", s->join, "Join small IndexedFaceSets under unneeded Separators");
  cmd->add_flag("--no-lines", s->no_lines, "Drop faces that collapse into lines");
  cmd->add_flag("--no-quads", s->no_quads, "Split every quadrilateral into triangles");
  cmd->add_option("--quad-split-angle", s->quad_split_angle,
                  "Split quads bent more than this (radians)")
      ->capture_default_str()
      ->check(kFiniteNumber)
      ->check(CLI::Range(0.0, 3.1416));
  cmd->add_option("--export", s->export_flavour, "LOD centre: spec, performer or reducer")
      ->capture_default_str()
      ->check(CLI::IsMember({"spec", "performer", "reducer"}));
  cmd->add_option("--extract", s->extract, "Write only level K of every shape (-1: only clean)")
      ->check(kFiniteNumber)
      ->check(CLI::Range(-1, 1000));
  cmd->add_option("--stats", s->stats,
                  "Write statistics as JSON to this file (- = stdout; .gz: gzip-compressed)");
  cmd->add_option("--verbose", s->verbose,
                  "Show messages of these categories: coord, material, normal, texcoord, face, "
                  "line, join, triangulator")
      ->delimiter(',');
  cmd->add_option("--threads", s->threads, "Worker threads (0: all cores)")
      ->check(kFiniteNumber)
      ->check(CLI::NonNegativeNumber);
  add_scene_read_options(*cmd, s->read);
  add_writer_options(*cmd, s->write);
  cmd->callback([s, &run] { run = [s] { return run_lod(*s); }; });
}

}  // namespace lodforge::apps
