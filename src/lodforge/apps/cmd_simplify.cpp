// `lodforge simplify MESH -o OUT (--ratio R | --triangles N) [--error E]
//                    [--method cluster|decimate|qem] [--format F] [--ascii] [--json]`:
// simplifies one surface with one of the three
// simplifiers of simplify/ and writes the result as a mesh file.
//
// Targets (decision table; usage errors exit 2, checked before any file is read):
//
// | given                         | meaning                                        |
// |-------------------------------|------------------------------------------------|
// | --ratio R, R in (0, 1]        | at most floor(R x input) triangles             |
// | --triangles N, N >= 1         | at most N triangles                            |
// | --error E, E >= 0             | as few triangles as the error budget allows    |
// | --error with a count          | both limits apply: stop at whichever comes     |
// |                               | first (count met, or next step exceeds E)      |
// | --ratio and --triangles       | usage error: one count only                    |
// | none                          | usage error                                    |
//
// Methods (simplify/): qem = quadric_collapse, decimate = vertex_decimation
// (both land at or just below a count), cluster = vertex_clustering (its
// levels fall at octree depths; the first at or below the count is written
// and stop_detail says how far below it is).
//
// "error" is the same for every method (lod/measured_simplify.h): the
// measured largest distance from the result to the input, enlarged by the
// pipeline's margin, so an upper bound on the one-sided Hausdorff distance;
// --error E gives the smallest result found whose error is <= E. The
// simplifier's own figure is kept as simplifier_estimate.
//
// Stopping short of the target (no allowed operation left) is a result, not
// an error: exit 0, the reason in stop_reason / stop_detail.
//
// Out of core (simplify/out_of_core_clustering.h, Lindstrom 2000): with
// --method cluster the input is streamed instead of loaded when
//
// | given                              | streamed                                  |
// |------------------------------------|-------------------------------------------|
// | --out-of-core                      | always (a file it cannot stream: exit 1)  |
// | neither                            | when the input is a binary PLY or STL and |
// |                                    | its faces x kInMemoryBytesPerTriangle     |
// |                                    | exceed the memory budget: --max-memory,   |
// |                                    | default 8 GiB or the process's address-   |
// |                                    | space limit (ulimit -v) if smaller        |
// | --out-of-core, method not cluster  | usage error                               |
//
// A streamed run cannot measure the error (that needs the input in memory):
// `error` is then the clustering's bound on the displacement of an input
// vertex (error_kind says so), --error bounds that, and `lodforge compare`
// measures the surface deviation afterwards.
//
// JSON keys (stdout, --json): input, output, method, input_vertices,
// input_triangles, target_triangles (null with --error alone), max_error
// (null without --error), output_vertices, output_triangles, output_lines,
// error, error_kind, simplifier_estimate,
// stop_reason, stop_detail, simplifier_runs (passes over the file when
// streamed), measurements, out_of_core, time_ms (the
// simplification and its measurements: no file reading or writing;
// steady_clock; streamed, the passes over the input are the simplification
// and count). JSON has no infinity: a figure that is not finite prints as
// null (vertex clustering's displacement overflows float beyond about 1e19).
#include <fmt/core.h>

#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include <sys/resource.h>

#include "lodforge/apps/commands.h"
#include "lodforge/apps/load_geometry.h"
#include "lodforge/core/error.h"
#include "lodforge/core/memory_budget.h"
#include "lodforge/core/output_path.h"
#include "lodforge/core/progress.h"
#include "lodforge/lod/measured_simplify.h"
#include "lodforge/lod/simplify_levels.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/mesh/triangle_stream.h"
#include "lodforge/simplify/out_of_core_clustering.h"

namespace lodforge::apps {
namespace {

std::string error_kind() {
  return fmt::format(
      "measured: largest distance from the result to the input, sampled and refined, x {} "
      "(a sampled measurement with a margin, not a proof; 10^6-sample measurements stay below it "
      "in bench/simplify_error_check.py)",
      kErrorMargin);
}

std::string bound_kind() {
  return "bound: largest distance from an input vertex to its cell's point (at most the "
         "cell diagonal), not the surface deviation: `lodforge compare` measures that";
}

/// Peak memory of the in-memory clustering path (reading, clustering, the
/// measured error) per input triangle: 297 MB were measured for a torus of
/// 1 M triangles (/usr/bin/time, Release).
constexpr double kInMemoryBytesPerTriangle = 300;

/// The memory budget of --max-memory's default: 8 GiB, or the address-space
/// or data limit of the process (ulimit -v / -d) when smaller.
double default_max_memory_gib() {
  std::uint64_t limit = kDefaultMemoryBudget;
  for (int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit r{};
    if (::getrlimit(resource, &r) == 0 && r.rlim_cur != RLIM_INFINITY)
      limit = std::min<std::uint64_t>(limit, r.rlim_cur);
  }
  return double(limit) / double(std::uint64_t{1} << 30);
}

nlohmann::ordered_json finite_or_null(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

struct SimplifySettings {
  std::string input;
  std::string output;
  std::optional<double> ratio;
  std::optional<std::size_t> triangles;
  std::optional<double> max_error;
  std::string method = "qem";
  std::string format;  // empty: from the output's extension
  bool ascii = false;
  bool json = false;
  bool quiet = false;
  bool out_of_core = false;
  double max_memory_gib = default_max_memory_gib();
  SceneReadSettings read;
};

SimplifyMethod method_named(const std::string& name) {
  if (name == "cluster") return SimplifyMethod::kCluster;
  if (name == "decimate") return SimplifyMethod::kDecimate;
  return SimplifyMethod::kQem;
}

/// Usage checks that need more than one option; throws CLI::ValidationError
/// (exit 2).
void check_usage(const SimplifySettings& s) {
  if (s.ratio && s.triangles)
    throw CLI::ValidationError("give one count: --ratio or --triangles, not both");
  if (!s.ratio && !s.triangles && !s.max_error)
    throw CLI::ValidationError("give a target: --ratio R, --triangles N and/or --error E");
  if (s.ratio && !(*s.ratio > 0 && *s.ratio <= 1))
    throw CLI::ValidationError(fmt::format("--ratio {} is outside (0, 1]", *s.ratio));
  if (s.triangles && *s.triangles == 0)
    throw CLI::ValidationError("--triangles must be at least 1");
  if (s.max_error && !(*s.max_error >= 0 && std::isfinite(*s.max_error)))
    throw CLI::ValidationError(fmt::format("--error {} must be finite and >= 0", *s.max_error));
  if (s.out_of_core && s.method != "cluster")
    throw CLI::ValidationError("--out-of-core streams the input through --method cluster only");
  if (!(s.max_memory_gib >= 0))
    throw CLI::ValidationError(fmt::format("--max-memory {} must be >= 0", s.max_memory_gib));
  if (s.format.empty() && format_from_path(s.output) == MeshFormat::kAuto)
    throw CLI::ValidationError(fmt::format(
        "cannot tell the output format of '{}': use .ply, .obj, .off or .stl, or --format",
        s.output));
}

MeshFormat format_named(const std::string& name) {
  if (name == "ply") return MeshFormat::kPly;
  if (name == "obj") return MeshFormat::kObj;
  if (name == "off") return MeshFormat::kOff;
  if (name == "stl") return MeshFormat::kStl;
  return MeshFormat::kAuto;
}

SimplifyTarget target_of(const SimplifySettings& s) {
  SimplifyTarget target;
  if (s.ratio) target.ratio = static_cast<float>(*s.ratio);
  if (s.triangles) target.triangles = *s.triangles;
  if (s.max_error) target.max_error = static_cast<float>(*s.max_error);
  return target;
}

/// What both paths report.
struct Summary {
  std::uint64_t input_vertices = 0, input_triangles = 0;
  const SimplifyResult* result = nullptr;
  double error = 0;
  std::string error_kind;
  std::size_t runs = 0, measurements = 0;
  bool out_of_core = false;
  double time_ms = 0;
};

int report(const SimplifySettings& s, const Summary& m) {
  const SimplifyResult& r = *m.result;
  const SimplifyTarget target = target_of(s);
  const bool by_count = s.ratio || s.triangles;
  const std::size_t target_triangles =
      target.triangle_target(static_cast<std::size_t>(m.input_triangles));
  if (s.json) {
    nlohmann::ordered_json j;
    j["input"] = s.input;
    j["output"] = s.output;
    j["method"] = s.method;
    j["input_vertices"] = m.input_vertices;
    j["input_triangles"] = m.input_triangles;
    j["target_triangles"] = by_count ? nlohmann::ordered_json(target_triangles) : nullptr;
    j["max_error"] = s.max_error ? nlohmann::ordered_json(*s.max_error) : nullptr;
    j["output_vertices"] = r.mesh.vertex_count();
    j["output_triangles"] = r.mesh.triangle_count();
    j["output_lines"] = r.mesh.lines.size();
    j["error"] = finite_or_null(m.error);
    j["error_kind"] = m.error_kind;
    j["simplifier_estimate"] = finite_or_null(r.error);
    j["stop_reason"] = to_string(r.stop_reason);
    j["stop_detail"] = r.stop_detail;
    j["simplifier_runs"] = m.runs;
    j["measurements"] = m.measurements;
    j["out_of_core"] = m.out_of_core;
    j["time_ms"] = m.time_ms;
    fmt::print("{}\n", j.dump(2));
    return 0;
  }
  if (s.quiet) return 0;
  fmt::print(stderr, "{}: {} triangles, {} vertices{}\n", s.input, m.input_triangles,
             m.input_vertices, m.out_of_core ? " (streamed: out of core)" : "");
  fmt::print(stderr, "{} ({}): {} triangles, {} vertices", s.output, s.method,
             r.mesh.triangle_count(), r.mesh.vertex_count());
  if (!r.mesh.lines.empty()) fmt::print(stderr, ", {} line segments", r.mesh.lines.size());
  if (by_count) fmt::print(stderr, " (target {})", target_triangles);
  fmt::print(stderr,
             "\n  error {:.6g} ({})\n"
             "  stopped: {}: {}\n  time {:.1f} ms ({} {}, {} measurements)\n",
             m.error, m.error_kind, to_string(r.stop_reason), r.stop_detail, m.time_ms, m.runs,
             m.out_of_core ? "passes over the file" : "simplifier runs", m.measurements);
  return 0;
}

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

/// Whether the run streams the input (the table at the top).
bool streams(const SimplifySettings& s) {
  if (s.out_of_core) return true;
  if (s.method != "cluster" || s.max_memory_gib == 0 || !TriangleStream::accepts(s.input))
    return false;
  const TriangleStream probe(s.input);
  return double(probe.face_count()) * kInMemoryBytesPerTriangle >
         s.max_memory_gib * double(std::uint64_t{1} << 30);
}

int run_out_of_core(const SimplifySettings& s) {
  const TriangleStream stream(s.input);
  const auto start = std::chrono::steady_clock::now();
  const OutOfCoreClusteringResult r = out_of_core_clustering(stream, {.target = target_of(s)});
  const double time_ms = milliseconds_since(start);
  if (r.input_triangles == 0)
    throw DataError(fmt::format("{}: the surface is empty (no triangles to simplify)", s.input));
  write_mesh(r.mesh, s.output, {.format = format_named(s.format), .binary = !s.ascii});
  return report(s, {.input_vertices = stream.vertex_count(),
                    .input_triangles = r.input_triangles,
                    .result = &r,
                    .error = r.error,
                    .error_kind = bound_kind(),
                    .runs = static_cast<std::size_t>(r.passes),
                    .out_of_core = true,
                    .time_ms = time_ms});
}

int run_simplify(const SimplifySettings& s) {
  check_usage(s);
  std::vector<OutputPath> outputs = {{s.output, "the simplified mesh"}};
  if (s.json) outputs.push_back({"-", "the JSON summary (--json)"});
  check_output_paths(outputs, std::array{s.input});
  if (streams(s)) return run_out_of_core(s);
  // VRML scenes are flattened to one world-space mesh (level 0 of any LOD).
  TriangleMesh mesh = load_geometry(s.input, 0,
                                    {.quiet = s.quiet || s.json,
                                     .max_instances = s.read.max_instances,
                                     .max_triangles = s.read.max_triangles});
  if (mesh.triangle_count() == 0)
    throw DataError(fmt::format("{}: the surface is empty (no triangles to simplify)", s.input));

  auto start = std::chrono::steady_clock::now();
  const MeasuredSimplifyResult m = [&] {
    Progress bar("simplify", 0, stderr_progress(s.quiet));
    return simplify_measured(
        mesh,
        {.method = method_named(s.method), .target = target_of(s), .progress = bar.callback()});
  }();
  const double time_ms = milliseconds_since(start);
  write_mesh(m.result.mesh, s.output, {.format = format_named(s.format), .binary = !s.ascii});
  return report(s, {.input_vertices = mesh.vertex_count(),
                    .input_triangles = mesh.triangle_count(),
                    .result = &m.result,
                    .error = m.error,
                    .error_kind = error_kind(),
                    .runs = m.simplifier_runs,
                    .measurements = m.measurements,
                    .time_ms = time_ms});
}

}  // namespace

void add_simplify_command(CLI::App& app, Runner& run) {
  auto s = std::make_shared<SimplifySettings>();
  CLI::App* cmd = app.add_subcommand(
      "simplify",
      "Simplify one surface (mesh file, or a VRML 1.0, Inventor, VRML97, X3D classic or glTF "
      "scene flattened in world space)");
  cmd->footer(
      "Targets: exactly one count (--ratio or --triangles) and/or --error; with a count and\n"
      "--error both limits apply and the first one met stops. Stopping short of the target\n"
      "(nothing left that may be removed) is not an error; the reason is reported.\n"
      "Methods:\n"
      "  qem       quadric edge collapse (best quality); count met at or just below\n"
      "  decimate  vertex decimation (Schroeder); count met at or just below\n"
      "  cluster   octree vertex clustering; its levels fall at octree depths: the first\n"
      "            AT OR BELOW the count is written (how far below is reported)\n"
      "error (model units, every method) = the measured largest distance from the result\n"
      "to the input x 1.1, an upper bound on the one-sided Hausdorff distance; --error E\n"
      "gives the smallest result found whose error is <= E (a measured search).\n"
      "Out of core: with --method cluster, a binary PLY or STL whose in-memory run would\n"
      "need more than --max-memory (about 300 bytes a triangle), or any input with\n"
      "--out-of-core, is streamed through Lindstrom's grid clustering instead: memory\n"
      "follows the output, a few passes over the file, the count met within 70-100 %.\n"
      "Its error cannot be measured without the input in memory: it is a bound on the\n"
      "displacement of an input vertex (<= the cell diagonal; --error bounds it), not\n"
      "the surface deviation; run `lodforge compare INPUT OUTPUT` for that.\n"
      "time_ms (--json) covers the simplification and its measurements, not file I/O\n"
      "(streamed: the passes over the input are the simplification and count).\n"
      "Exit codes: 0 done, 1 bad input (unreadable, empty surface), 2 bad usage.\n");
  cmd->add_option("MESH", s->input,
                  "Input: PLY, OBJ, OFF, STL (optionally .gz), VRML 1.0 / Inventor, VRML97 / X3D "
                  "classic or XML (.wrl, .x3dv, .x3d) or glTF scene; - = stdin")
      ->required();
  cmd->add_option(
         "-o,--output", s->output,
         "Output mesh, written atomically; format from the extension "
         "(.ply, .obj, .off, .stl; x.ply.gz: PLY, gzip-compressed) or --format; - = stdout")
      ->required();
  cmd->add_option("--ratio", s->ratio, "Keep at most R x the input's triangles, R in (0, 1]");
  cmd->add_option("--triangles", s->triangles, "Keep at most N triangles (N >= 1)");
  cmd->add_option("--error", s->max_error,
                  "Error budget in model units, against the measured error (below); alone: "
                  "the smallest result found within it");
  cmd->add_option("--method", s->method, "cluster, decimate or qem (default qem)")
      ->check(CLI::IsMember({"cluster", "decimate", "qem"}));
  cmd->add_option("--format", s->format, "Output format: ply, obj, off or stl (default: extension)")
      ->check(CLI::IsMember({"ply", "obj", "off", "stl"}));
  cmd->add_flag("--out-of-core", s->out_of_core,
                "Stream the input (binary PLY or STL) through out-of-core clustering, whatever "
                "its size (--method cluster only)");
  cmd->add_option("--max-memory", s->max_memory_gib,
                  "GiB the in-memory cluster run may take; a binary PLY / STL needing more is "
                  "streamed (default 8, or ulimit -v / -d if smaller; 0 = never stream)")
      ->default_str(fmt::format("{:.3g}", s->max_memory_gib));
  cmd->add_flag("--ascii", s->ascii, "ASCII PLY / STL (default binary)");
  cmd->add_flag("--json", s->json, "Print the JSON summary on stdout (no human text)");
  cmd->add_flag("-q,--quiet", s->quiet,
                "No summary, no reader warnings and no progress bar on stderr");
  add_expansion_options(*cmd, s->read);
  cmd->callback([s, &run] { run = [s] { return run_simplify(*s); }; });
}

}  // namespace lodforge::apps
