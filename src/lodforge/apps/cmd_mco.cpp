// `lodforge mco build MESH|DIR|CONF -o MODEL.mco [--resolution N] [--close-holes]
//                    [--metric area|distance] [--surface-vertices] [--threads T]`
// `lodforge mco extract MODEL.mco -o OUT (--triangles N | --percent P | --priority N)`
// `lodforge mco extract MODEL.mco -o OUT --camera X,Y,Z --look-at X,Y,Z [--up X,Y,Z]
//                      [--fov RAD] [--pixels H] [--aspect W:H] [--pixel-error E]`
// `lodforge mco info MODEL.mco [--json]`
// `lodforge mco query MODEL.mco (--ray OX,OY,OZ,DX,DY,DZ | --point X,Y,Z)...
//                    [--percent P | --priority N]`
// `lodforge mco scan MESH --views K -o DIR [--resolution N]`
// The marching-cube octree: build once, extract any level later.
// Human text goes to stderr; `info --json` and `query` print JSON on stdout.
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>

#include "lodforge/apps/commands.h"
#include "lodforge/apps/common_options.h"
#include "lodforge/apps/load_geometry.h"
#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/core/output_path.h"
#include "lodforge/core/progress.h"
#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "lodforge/mcoctree/mc_lod_model.h"
#include "lodforge/mcoctree/mc_parts.h"
#include "lodforge/mcoctree/mc_query.h"
#include "lodforge/mcoctree/mco_file.h"
#include "lodforge/mcoctree/range_scan.h"
#include "lodforge/mcoctree/scan_mesh.h"
#include "lodforge/mcoctree/view_extract.h"
#include "lodforge/mesh/mesh_io.h"

namespace lodforge::apps {
namespace {

// Range scans rather than a mesh: a directory, a .conf, or a PLY whose header
// declares a range_grid element.
bool is_range_input(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) return true;
  fs::path p(path);
  if (p.extension() == ".conf") return true;
  if (p.extension() != ".ply") return false;
  std::ifstream in(path, std::ios::binary);
  std::string header(4096, '\0');
  in.read(header.data(), static_cast<std::streamsize>(header.size()));
  header.resize(static_cast<std::size_t>(in.gcount()));
  auto end = header.find("end_header");
  return header.substr(0, end).find("element range_grid") != std::string::npos;
}

}  // namespace

// Runs `f`, naming `input` in the message of a DataError that does not.
template <class F>
auto named(const std::string& input, F&& f) {
  try {
    return f();
  } catch (const DataError& e) {
    if (std::string_view(e.what()).starts_with(input)) throw;
    throw DataError(input + ": " + e.what());
  }
}

namespace {

struct Build {
  std::string input, output;
  int resolution = 0;
  int threads = 0;
  bool close_holes = false;
  bool surface_vertices = false;
  std::string metric = "area";
  double max_memory_gib = double(kDefaultMemoryBudget >> 30);
  SceneReadSettings read;
};

std::string box_text(const Box3& b) {
  return fmt::format("[{:.4g} {:.4g} {:.4g}]..[{:.4g} {:.4g} {:.4g}]", b.lo.x, b.lo.y, b.lo.z,
                     b.hi.x, b.hi.y, b.hi.z);
}

// Names each input part that left no surface and the resolution that would
// keep it.
void warn_vanished_parts(const std::string& input, const TriangleMesh& mesh,
                         const McPartsCheck& parts, float cell) {
  for (const McPart& p : parts.vanished) {
    const int keep = resolution_to_keep(p, mesh.bounds());
    fmt::print(stderr,
               "warning: {}: the input's part of {} triangles in {} left no surface (thinner "
               "than about a cell, {:.4g}); {}\n",
               input, p.triangles, box_text(p.bounds), cell,
               keep <= 1000 ? fmt::format("--resolution {} would keep it", keep)
                            : std::string("no resolution up to 1000 keeps it"));
  }
}

// Says when the model's surface does not keep the input's connected parts,
// and where its smallest parts are.
void warn_lost_parts(const std::string& input, const TriangleMesh& mesh, const McLodModel& model) {
  const McPartsCheck parts = check_mc_parts(mesh, extract_mc_mesh(model).mesh, 3, model.cell_size);
  if (parts.kept()) return;
  warn_vanished_parts(input, mesh, parts, model.cell_size);
  const std::string counts =
      fmt::format("{}: at full resolution the model has {} connected part{} where the input has {}",
                  input, parts.model_parts, parts.model_parts == 1 ? "" : "s", parts.input_parts);
  if (parts.model_parts < parts.input_parts) {
    fmt::print(stderr,
               "warning: {}: parts closer than about a cell ({:.4g}) join, a part smaller than "
               "one vanishes. A finer --resolution keeps them apart\n",
               counts, model.cell_size);
    return;
  }
  std::string smallest;
  for (const McPart& p : parts.smallest)
    smallest += fmt::format("{}{} triangles in {}", smallest.empty() ? "" : "; ", p.triangles,
                            box_text(p.bounds));
  fmt::print(stderr,
             "warning: {}: a part thinner than about a cell ({:.4g}) comes apart into pieces; "
             "the smallest: {}. A finer --resolution keeps what is at least a cell thick\n",
             counts, model.cell_size, smallest);
}

// Builds the octree of a mesh or of range scans and writes the model.
int run_mco_build(const Build& b) {
  check_output_paths(std::array{OutputPath{b.output, "the model"}}, std::array{b.input});
  auto t0 = std::chrono::steady_clock::now();
  McBuildOptions options{
      .resolution = b.resolution,
      .threads = b.threads,
      .holes = b.close_holes ? McHoles::kCapped : McHoles::kOpen,
      .metric = b.metric == "distance" ? McPriorityMetric::kDistance : McPriorityMetric::kArea,
      .place_coarse_vertices = !b.surface_vertices,
      .max_memory = static_cast<std::uint64_t>(b.max_memory_gib * double(1 << 30))};
  McBuildResult r;
  // The bar runs while the octree is built (made once the input is read,
  // so that the reader's warnings come before it).
  auto build_with_bar = [&](const auto& input) {
    Progress bar("mco build", 0, stderr_progress(b.read.quiet));
    McBuildOptions drawn = options;
    drawn.progress = bar.callback();
    return named(b.input, [&] { return build_mc_octree(input, drawn); });
  };
  std::string what;
  TriangleMesh mesh;  // a mesh input, kept to compare its parts with the model's
  if (is_range_input(b.input)) {
    auto scans = read_range_scans(b.input);
    std::size_t points = 0;
    for (const auto& sc : scans)
      for (auto g : sc.grid) points += g >= 0;
    r = build_with_bar(scans);
    what = fmt::format(
        "{} range scans ({} points; lattice: {} measured, {} carved, {} flooded; {} voids "
        "filled, {} bubbles dropped, {} pits filled)",
        scans.size(), points, r.stats.band_points, r.stats.carved_points, r.stats.flooded_points,
        r.stats.filled_voids, r.stats.dropped_parts, r.stats.sign_flips);
  } else {
    mesh = load_geometry(b.input, 0, b.read);
    if (const double bytes = mc_build_bytes(mesh.bounds(), b.resolution);
        bytes > double(std::uint64_t{1} << 30))
      fmt::print(stderr,
                 "warning: {}: the lattice at resolution {} takes about {:.1f} GiB; the build "
                 "may take minutes\n",
                 b.input, b.resolution, bytes / double(std::uint64_t{1} << 30));
    r = build_with_bar(mesh);
    what = fmt::format("{} triangles ({} part bridge{})", mesh.triangle_count(),
                       r.stats.part_bridges, r.stats.part_bridges == 1 ? "" : "s");
  }
  McLodModel model = compile_mc_lod(r.tree);
  write_mco_file(model, b.output);
  if (!mesh.triangles.empty()) warn_lost_parts(b.input, mesh, model);
  double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  fmt::print(stderr,
             "{}: {} -> {} nodes ({} leaves), {} vertices, {} priorities, {} triangles at "
             "full resolution, {:.1f} bytes per triangle at run time; {:.2f} s\n",
             b.output, what, r.tree.nodes.size(), r.stats.leaves, model.positions.size(),
             model.priorities(), model.full_triangles(),
             static_cast<double>(model.memory_bytes()) /
                 static_cast<double>(std::max<std::uint64_t>(model.full_triangles(), 1)),
             s);
  return 0;
}

void add_mco_build(CLI::App* mco, Runner& run) {
  auto b = std::make_shared<Build>();
  CLI::App* build = mco->add_subcommand("build", "Build the octree of a mesh and write MODEL.mco");
  build
      ->add_option("INPUT", b->input,
                   "Mesh (PLY, OBJ, OFF, STL), VRML 1.0 scene, or range scans: a .conf, a "
                   "directory of range-grid PLYs (with its .conf) or one range-grid PLY")
      ->required();
  build->add_option("-o,--output", b->output, "Model file to write (.mco)")->required();
  build
      ->add_option("--resolution", b->resolution,
                   "Finest cells across the longest side (2..1000); 0 (default): about as many "
                   "triangles at full resolution as the input has (range scans: cells twice the "
                   "point spacing)")
      ->check(kFiniteNumber)
      ->check(CLI::Range(0, 1000))
      ->check([](const std::string& v) {
        return v == "1" ? std::string("use 0 (automatic) or 2..1000") : std::string();
      });
  build->add_flag("--close-holes", b->close_holes,
                  "Close the holes of an open mesh (a watertight model; default: the model "
                  "has borders where the input has them)");
  build
      ->add_option("--metric", b->metric,
                   "Priority metric: area (default; the thesis's area difference) or distance "
                   "(how far the finer surface lies from a coarse cell: lower error at every "
                   "level, about 10 % more build time)")
      ->check(CLI::IsMember({"area", "distance"}));
  build->add_flag("--surface-vertices", b->surface_vertices,
                  "Keep every vertex of every level on the input surface (default: coarse "
                  "levels' vertices move off it to where their triangles straddle the surface, "
                  "for a lower deviation)");
  build->add_option("--threads", b->threads, "Worker threads (0: all cores)")
      ->check(kFiniteNumber)
      ->check(CLI::NonNegativeNumber);
  build->add_flag("-q,--quiet", b->read.quiet,
                  "No reader warnings and no progress bar (the one-line summary stays)");
  add_expansion_options(*build, b->read);
  build
      ->add_option("--max-memory", b->max_memory_gib,
                   "Refuse a build estimated to take more memory than this, in GiB (0 = no limit)")
      ->capture_default_str()
      ->check(kFiniteNumber)
      ->check(CLI::NonNegativeNumber);
  build->callback([b, &run] { run = [b] { return run_mco_build(*b); }; });
}

// A model file, or a file cut short (a partial download): read up to the
// last priority it holds in full, with a warning saying what is missing.
// `full_triangles` is the whole model's count at full resolution (the held
// part's finest count if the file is cut and does not record it).
struct LoadedModel {
  McLodModel model;
  McoFileSummary summary;
  std::uint64_t full_triangles = 0;
};

LoadedModel load_model(const std::string& path, std::int64_t max_priority = -1,
                       bool quiet = false) {
  const std::string data = read_file(path);
  LoadedModel out;
  out.summary = summarize_mco_data(data, path);
  const McoFileSummary& s = out.summary;
  if (!quiet && s.truncated() && s.complete_priorities > 0 &&
      (max_priority < 0 || static_cast<std::uint64_t>(max_priority) >= s.complete_priorities))
    fmt::print(stderr,
               "warning: {}: the file ends after priority {} of {} ({} bytes); only the levels "
               "up to it can be extracted\n",
               path, s.complete_priorities - 1, s.priorities, data.size());
  out.model = read_mco_data(data, path, {.max_priority = max_priority, .prefix = true});
  out.full_triangles = s.full_triangles ? s.full_triangles : out.model.full_triangles();
  if (!quiet && s.truncated() && !s.full_triangles)
    fmt::print(stderr,
               "warning: {}: a version {} file does not record its full triangle count; "
               "percentages are of the {} triangles it holds\n",
               path, s.version, out.full_triangles);
  return out;
}

// The numbers of a comma-separated option value, exactly `count` of them,
// finite floats; DataError naming the option and the expected form.
std::vector<float> parse_numbers(const std::string& value, std::size_t count,
                                 const std::string& option, const std::string& form) {
  std::vector<float> out;
  const char* p = value.data();
  const char* const end = p + value.size();
  while (p <= end) {
    const char* comma = std::find(p, end, ',');
    double x = 0;
    auto [stop, ec] = std::from_chars(p, comma, x);
    if (ec != std::errc{} || stop != comma || !std::isfinite(static_cast<float>(x))) {
      out.clear();
      break;
    }
    out.push_back(static_cast<float>(x));
    p = comma + 1;
  }
  if (out.size() != count)
    throw DataError(fmt::format("{} '{}': expected {} ({} finite numbers separated by commas)",
                                option, value, form, count));
  return out;
}

struct Extract {
  std::string input, output;
  std::int64_t triangles = -1, priority = -1;
  double percent = -1;
  bool quiet = false;
  // View-dependent extraction (--camera): the camera as given, parsed in run.
  std::string camera, look_at, up = "0,1,0", fov, pixels, aspect, pixel_error;
};

Vec3 parse_vec3(const std::string& value, const std::string& option) {
  auto v = parse_numbers(value, 3, option, "X,Y,Z");
  return {v[0], v[1], v[2]};
}

// One number of an option, in (0, most]; `fallback` when not given.
double parse_positive(const std::string& value, const std::string& option, const std::string& form,
                      double most, double fallback) {
  if (value.empty()) return fallback;
  const double x = parse_numbers(value, 1, option, form)[0];
  if (!(x > 0 && x <= most))
    throw DataError(fmt::format("{} '{}': expected {} (a number > 0{})", option, value, form,
                                most < HUGE_VAL ? fmt::format(" and below {:g}", most) : ""));
  return x;
}

// --aspect: W:H (16:9), W/H or one number (1.778); `fallback` when not given.
double parse_aspect(const std::string& value, double fallback) {
  if (value.empty()) return fallback;
  const DataError bad(fmt::format(
      "--aspect '{}': expected W:H, W/H or a number (the screen's width over its height, > 0)",
      value));
  std::string v = value;
  std::replace_if(
      v.begin(), v.end(), [](char c) { return c == ':' || c == '/'; }, ',');
  const bool ratio = v.find(',') != std::string::npos;
  std::vector<float> n;
  try {
    n = parse_numbers(v, ratio ? 2 : 1, "--aspect", "W:H");
  } catch (const DataError&) {
    throw bad;
  }
  const double a = ratio ? double(n[0]) / double(n[1]) : double(n[0]);
  if (!(n[0] > 0) || (ratio && !(n[1] > 0)) || !std::isfinite(a)) throw bad;
  return a;
}

// `mco extract --camera`: the view-dependent cut of the whole model.
int run_view_extract(const Extract& e) {
  McViewOptions o;
  o.camera.position = parse_vec3(e.camera, "--camera");
  if (e.look_at.empty())
    throw CLI::ValidationError("mco extract", "--camera needs --look-at X,Y,Z");
  o.camera.look_at = parse_vec3(e.look_at, "--look-at");
  o.camera.up = parse_vec3(e.up, "--up");
  o.camera.fov =
      parse_positive(e.fov, "--fov", "RAD", std::nextafter(std::numbers::pi, 0.0), o.camera.fov);
  o.camera.pixels = parse_positive(e.pixels, "--pixels", "H", HUGE_VAL, o.camera.pixels);
  o.camera.aspect = parse_aspect(e.aspect, o.camera.aspect);
  o.pixel_error = parse_positive(e.pixel_error, "--pixel-error", "E", HUGE_VAL, o.pixel_error);
  const LoadedModel loaded = load_model(e.input, -1, e.quiet);
  if (loaded.summary.truncated())
    throw DataError(e.input + ": view-dependent extraction needs the whole model");
  const McViewResult r = extract_mc_view(loaded.model, o);
  write_mesh(r.mesh, e.output);
  fmt::print(stderr,
             "{}: view-dependent, {} triangles ({:.1f}% of {}), {} vertices, worst projected "
             "error {:.3g} px (budget {:g}), {} nodes expanded ({} for crack-freedom)\n",
             e.output, r.mesh.triangle_count(),
             100.0 * double(r.mesh.triangle_count()) /
                 double(std::max<std::uint64_t>(loaded.model.full_triangles(), 1)),
             loaded.model.full_triangles(), r.mesh.vertex_count(), r.pixel_error, o.pixel_error,
             r.expanded, r.forced);
  return 0;
}

void add_mco_extract(CLI::App* mco, Runner& run) {
  auto e = std::make_shared<Extract>();
  CLI::App* extract = mco->add_subcommand("extract", "Extract one level of detail from MODEL.mco");
  extract->add_option("MODEL", e->input, "Model file (.mco)")->required();
  extract->add_option("-o,--output", e->output, "Mesh to write (format from the extension)")
      ->required();
  auto* ot = extract->add_option("--triangles", e->triangles, "Triangle budget")
                 ->check(kFiniteNumber)
                 ->check(CLI::NonNegativeNumber);
  auto* op =
      extract->add_option("--percent", e->percent, "Percent of the full-resolution triangles")
          ->check(kFiniteNumber)
          ->check(CLI::Range(0.0, 100.0));
  auto* on = extract->add_option("--priority", e->priority, "Priority number N")
                 ->check(kFiniteNumber)
                 ->check(CLI::NonNegativeNumber);
  ot->excludes(op)->excludes(on);
  op->excludes(on);
  auto* oc = extract->add_option("--camera", e->camera,
                                 "View-dependent: the camera position X,Y,Z (with --look-at)");
  oc->excludes(ot)->excludes(op)->excludes(on);
  auto view = [&](const char* name, auto& value, const char* what) {
    return extract->add_option(name, value, what)->needs(oc);
  };
  view("--look-at", e->look_at, "View-dependent: the point looked at, X,Y,Z");
  view("--up", e->up, "View-dependent: the up direction X,Y,Z (default 0,1,0)");
  view("--fov", e->fov, "View-dependent: vertical field of view in radians (default pi/4)");
  view("--pixels", e->pixels, "View-dependent: screen height in pixels (default 1080)");
  view("--aspect", e->aspect,
       "View-dependent: screen width over height, W:H, W/H or a number (default 16:9)");
  view("--pixel-error", e->pixel_error,
       "View-dependent: largest projected error in pixels (default 1)");
  extract->add_flag("-q,--quiet", e->quiet, "No warnings (the one-line summary stays)");
  extract->callback([e, &run] {
    run = [e] {
      check_output_paths(std::array{OutputPath{e->output, "the extracted mesh"}},
                         std::array{e->input});
      if (!e->camera.empty()) return run_view_extract(*e);
      // --priority N reads only what priorities 0..N need (the file is
      // progressive: a prefix, e.g. a partial download, is enough).
      const LoadedModel loaded = load_model(e->input, e->priority, e->quiet);
      const McLodModel& model = loaded.model;
      // A percentage is of the whole model, whatever part of it the file holds.
      std::int64_t triangles = e->triangles;
      if (e->percent >= 0)
        triangles = std::llround(double(loaded.full_triangles) * e->percent / 100.0);
      auto r = extract_mc_mesh(model, {.priority = e->priority, .triangles = triangles});
      if (r.clamped && !e->quiet)
        fmt::print(stderr, "warning: request beyond the {}, clamped to priority {}\n",
                   loaded.summary.truncated() ? "levels the file holds" : "model's range",
                   r.priority);
      write_mesh(r.mesh, e->output);
      fmt::print(stderr, "{}: priority {} of {}{}, {} triangles, {} vertices", e->output,
                 r.priority, model.priorities(), e->priority >= 0 ? " read" : "",
                 r.mesh.triangle_count(), r.mesh.vertex_count());
      if (e->triangles >= 0 || e->percent >= 0)
        fmt::print(stderr, " (requested {}, nearest reachable)", triangles);
      fmt::print(stderr, "\n");
      return 0;
    };
  });
}

struct Info {
  std::string input;
  bool json = false;
};

void add_mco_info(CLI::App* mco, Runner& run) {
  auto i = std::make_shared<Info>();
  CLI::App* info = mco->add_subcommand("info", "Describe MODEL.mco");
  info->add_option("MODEL", i->input, "Model file (.mco)")->required();
  info->add_flag("--json", i->json, "Print JSON on stdout");
  info->callback([i, &run] {
    run = [i] {
      const LoadedModel loaded = load_model(i->input);
      const McLodModel& t = loaded.model;
      const McoFileSummary& s = loaded.summary;
      nlohmann::ordered_json j;
      j["file"] = i->input;
      j["version"] = s.version;
      j["truncated"] = s.truncated();
      j["file_priorities"] = s.priorities;
      j["depth"] = t.depth;
      j["cell_size"] = t.cell_size;
      j["origin"] = {t.origin.x, t.origin.y, t.origin.z};
      j["vertices"] = t.positions.size();
      j["cells"] = t.cell_count();
      j["intervals"] = t.intervals.size() - 1;
      j["stored_triangles"] = t.stored_triangles();
      j["priorities"] = t.priorities();
      j["full_triangles"] = loaded.full_triangles;
      j["held_triangles"] = t.full_triangles();
      j["colors"] = !t.colors.empty();
      j["memory_bytes"] = t.memory_bytes();
      nlohmann::ordered_json levels = nlohmann::ordered_json::array();
      for (int pct : {100, 80, 60, 40, 20, 5}) {
        const std::uint64_t want = loaded.full_triangles * pct / 100;
        auto n = priority_for_triangles(t, want);
        levels.push_back({{"percent", pct},
                          {"priority", n},
                          {"triangles", t.accumulated[n]},
                          {"held", want <= t.full_triangles()}});
      }
      j["levels"] = levels;
      if (i->json) {
        fmt::print("{}\n", j.dump(2));
        return 0;
      }
      fmt::print(stderr, "{}: marching-cube octree, version {}{}\n", i->input, s.version,
                 s.truncated() ? fmt::format(", cut short: priorities 0..{} of {} held",
                                             t.priorities(), s.priorities)
                               : "");
      fmt::print(stderr,
                 "  depth {} (cell {:.6g}), {} cells, {} intervals, {} stored triangles, {} "
                 "vertices{}\n",
                 t.depth, t.cell_size, t.cell_count(), t.intervals.size() - 1, t.stored_triangles(),
                 t.positions.size(), t.colors.empty() ? "" : ", coloured");
      fmt::print(stderr, "  {} priorities, {} triangles at full resolution, {} bytes in memory\n",
                 t.priorities(), loaded.full_triangles, t.memory_bytes());
      for (const auto& l : levels)
        fmt::print(stderr, "  {:3}%: priority {:8}, {:9} triangles{}\n", l["percent"].get<int>(),
                   l["priority"].get<std::uint32_t>(), l["triangles"].get<std::uint64_t>(),
                   l["held"].get<bool>() ? "" : " (the finest level the file holds)");
      return 0;
    };
  });
}

struct Query {
  std::string input;
  std::vector<std::string> rays, points;
  std::int64_t priority = -1;
  double percent = -1;
  bool quiet = false;
};

std::vector<float> parse_ray(const std::string& value) {
  auto v = parse_numbers(value, 6, "--ray", "OX,OY,OZ,DX,DY,DZ");
  if (v[3] == 0 && v[4] == 0 && v[5] == 0)
    throw DataError(fmt::format("--ray '{}': the direction DX,DY,DZ is zero", value));
  return v;
}
std::vector<float> parse_point(const std::string& value) {
  return parse_numbers(value, 3, "--point", "X,Y,Z");
}

// A float as the double of its shortest decimal form, so that JSON shows
// 0.1 rather than 0.10000000149011612.
double json_float(float x) {
  char buf[32];
  auto end = std::to_chars(buf, buf + sizeof buf, x).ptr;
  double d = 0;
  std::from_chars(buf, end, d);
  return d;
}

nlohmann::ordered_json json_of(const float* v, int n) {
  nlohmann::ordered_json j = nlohmann::ordered_json::array();
  for (int k = 0; k < n; ++k) j.push_back(json_float(v[k]));
  return j;
}
nlohmann::ordered_json json_of(Vec3 v) {
  return json_of(&v.x, 3);
}

// One query's answer as JSON: the query, then what it found.
nlohmann::ordered_json ray_json(const McQuery& q, const std::string& value) {
  auto v = parse_ray(value);
  const Vec3 o{v[0], v[1], v[2]}, d{v[3], v[4], v[5]};
  const McRayHit hit = q.ray(o, d);
  nlohmann::ordered_json j;
  j["ray"] = json_of(v.data(), 6);
  j["hit"] = hit.hit();
  if (hit.hit()) {
    j["distance"] = json_float(hit.distance);
    j["point"] = json_of(hit.point);
    j["normal"] = json_of(hit.normal);
    j["triangle"] = hit.triangle;
  }
  return j;
}

nlohmann::ordered_json point_json(const McQuery& q, const std::string& value) {
  auto v = parse_point(value);
  const McClosest c = q.closest({v[0], v[1], v[2]});
  nlohmann::ordered_json j;
  j["point"] = json_of(v.data(), 3);
  j["found"] = c.found();
  if (c.found()) {
    j["distance"] = json_float(c.distance);
    j["closest"] = json_of(c.point);
    j["triangle"] = c.triangle;
    j["inside"] = c.inside();
    j["side_known"] = !c.open;
  }
  return j;
}

void add_mco_query(CLI::App* mco, Runner& run) {
  auto qs = std::make_shared<Query>();
  CLI::App* query = mco->add_subcommand(
      "query",
      "Ray hits, closest points, signed distances and inside tests on MODEL.mco (JSON on stdout)");
  query->add_option("MODEL", qs->input, "Model file (.mco)")->required();
  auto* oray = query->add_option(
      "--ray", qs->rays,
      "Ray OX,OY,OZ,DX,DY,DZ (origin, direction): the first hit's distance, point, face normal "
      "and triangle (repeatable)");
  auto* opoint = query->add_option(
      "--point", qs->points,
      "Point X,Y,Z: the closest surface point, signed distance (negative inside) and whether "
      "it is inside (repeatable)");
  auto* op = query
                 ->add_option("--percent", qs->percent,
                              "Query the level with this percent of the full-resolution "
                              "triangles (default: full resolution)")
                 ->check(kFiniteNumber)
                 ->check(CLI::Range(0.0, 100.0));
  auto* on = query->add_option("--priority", qs->priority, "Query the level of priority N")
                 ->check(kFiniteNumber)
                 ->check(CLI::NonNegativeNumber);
  op->excludes(on);
  query->add_flag("-q,--quiet", qs->quiet, "No warnings and no summary line");
  query->callback([qs, query, oray, opoint, &run] {
    // The answers in the order the options were given.
    std::vector<bool> is_ray;
    for (const CLI::Option* o : query->parse_order())
      if (o == oray || o == opoint) is_ray.push_back(o == oray);
    run = [qs, is_ray] {
      if (is_ray.empty())
        throw CLI::ValidationError("mco query", "give at least one --ray or --point");
      // Bad numbers are reported before the model is read.
      for (const auto& v : qs->rays) parse_ray(v);
      for (const auto& v : qs->points) parse_point(v);
      const LoadedModel loaded = load_model(qs->input, qs->priority, qs->quiet);
      std::int64_t triangles = -1;
      if (qs->percent >= 0)
        triangles = std::llround(double(loaded.full_triangles) * qs->percent / 100.0);
      const McQuery q(loaded.model, {.priority = qs->priority, .triangles = triangles});
      nlohmann::ordered_json out = nlohmann::ordered_json::array();
      std::size_t r = 0, p = 0;
      for (bool ray : is_ray)
        out.push_back(ray ? ray_json(q, qs->rays[r++]) : point_json(q, qs->points[p++]));
      if (!qs->quiet)
        fmt::print(stderr, "{}: priority {} of {}, {} triangles, {} queries\n", qs->input,
                   q.priority(), loaded.model.priorities(), q.mesh().triangle_count(), out.size());
      // One answer per line: a JSON array, readable and easy to grep.
      std::string lines = "[";
      for (std::size_t k = 0; k < out.size(); ++k) lines += (k ? ",\n  " : "\n  ") + out[k].dump();
      fmt::print("{}\n]\n", lines);
      return 0;
    };
  });
}

struct Scan {
  std::string input, output;
  int views = 6, resolution = 256;
  SceneReadSettings read;
};

void add_mco_scan(CLI::App* mco, Runner& run) {
  auto sc = std::make_shared<Scan>();
  CLI::App* scan = mco->add_subcommand(
      "scan", "Synthetic range scans of a mesh: range-grid PLYs and a .conf in DIR");
  scan->add_option("MESH", sc->input, "Mesh (PLY, OBJ, OFF, STL) or VRML 1.0 scene")->required();
  scan->add_option("-o,--output", sc->output, "Directory to write the scans to")->required();
  scan->add_option("--views", sc->views, "Viewing directions, spread on the sphere (1..1000)")
      ->check(kFiniteNumber)
      ->check(CLI::Range(1, 1000));
  scan->add_option("--resolution", sc->resolution, "Grid points across each view (4..4096)")
      ->check(kFiniteNumber)
      ->check(CLI::Range(4, 4096));
  add_expansion_options(*scan, sc->read);
  scan->callback([sc, &run] {
    run = [sc] {
      TriangleMesh mesh = load_geometry(sc->input, 0, sc->read);
      auto scans = scan_mesh(mesh, {.views = sc->views, .resolution = sc->resolution});
      // The folder's files, checked before the first is written.
      std::vector<OutputPath> outputs;
      for (const auto& s : scans)
        outputs.push_back({(std::filesystem::path(sc->output) / s.name).string(), "a scan"});
      const std::string conf = "scans.conf";
      outputs.push_back({(std::filesystem::path(sc->output) / conf).string(), "the list of scans"});
      check_output_paths(outputs, std::array{sc->input});
      write_range_scans(scans, sc->output, conf);
      std::size_t points = 0;
      for (const auto& s : scans) points += s.points.size();
      fmt::print(stderr, "{}: {} scans of {}x{}, {} points{}, {}\n", sc->output, scans.size(),
                 sc->resolution, sc->resolution, points, mesh.has_colors() ? " (coloured)" : "",
                 conf);
      return 0;
    };
  });
}

}  // namespace

void add_mco_command(CLI::App& app, Runner& run) {
  CLI::App* mco = app.add_subcommand("mco", "Marching-cube octree: continuous levels of detail");
  mco->require_subcommand(1);
  add_mco_build(mco, run);
  add_mco_extract(mco, run);
  add_mco_info(mco, run);
  add_mco_query(mco, run);
  add_mco_scan(mco, run);
}

}  // namespace lodforge::apps
