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
// JSON keys (stdout, --json): input, output, method, input_vertices,
// input_triangles, target_triangles (null with --error alone), max_error
// (null without --error), output_vertices, output_triangles, output_lines,
// error, error_kind, simplifier_estimate,
// stop_reason, stop_detail, simplifier_runs, measurements, time_ms (the
// simplification and its measurements: no file reading or writing;
// steady_clock). JSON has no infinity: a figure that is not finite prints as
// null (vertex clustering's displacement overflows float beyond about 1e19).
#include <fmt/core.h>

#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "lodforge/apps/commands.h"
#include "lodforge/apps/load_geometry.h"
#include "lodforge/core/error.h"
#include "lodforge/core/output_path.h"
#include "lodforge/core/progress.h"
#include "lodforge/lod/measured_simplify.h"
#include "lodforge/lod/simplify_levels.h"
#include "lodforge/mesh/mesh_io.h"

namespace lodforge::apps {
namespace {

std::string error_kind() {
  return fmt::format(
      "measured: largest distance from the result to the input, sampled and refined, x {} "
      "(an upper bound that a denser measurement stays below)",
      kErrorMargin);
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

int run_simplify(const SimplifySettings& s) {
  check_usage(s);
  std::vector<OutputPath> outputs = {{s.output, "the simplified mesh"}};
  if (s.json) outputs.push_back({"-", "the JSON summary (--json)"});
  check_output_paths(outputs, std::array{s.input});
  // VRML scenes are flattened to one world-space mesh (level 0 of any LOD).
  TriangleMesh mesh = load_geometry(s.input, 0,
                                    {.quiet = s.quiet || s.json,
                                     .max_instances = s.read.max_instances,
                                     .max_triangles = s.read.max_triangles});
  if (mesh.triangle_count() == 0)
    throw DataError(fmt::format("{}: the surface is empty (no triangles to simplify)", s.input));

  SimplifyTarget target;
  if (s.ratio) target.ratio = static_cast<float>(*s.ratio);
  if (s.triangles) target.triangles = *s.triangles;
  if (s.max_error) target.max_error = static_cast<float>(*s.max_error);

  auto start = std::chrono::steady_clock::now();
  const MeasuredSimplifyResult m = [&] {
    Progress bar("simplify", 0, stderr_progress(s.quiet));
    return simplify_measured(
        mesh, {.method = method_named(s.method), .target = target, .progress = bar.callback()});
  }();
  double time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const SimplifyResult& r = m.result;

  write_mesh(r.mesh, s.output, {.format = format_named(s.format), .binary = !s.ascii});

  const bool by_count = s.ratio || s.triangles;
  if (s.json) {
    nlohmann::ordered_json j;
    j["input"] = s.input;
    j["output"] = s.output;
    j["method"] = s.method;
    j["input_vertices"] = mesh.vertex_count();
    j["input_triangles"] = mesh.triangle_count();
    j["target_triangles"] =
        by_count ? nlohmann::ordered_json(target.triangle_target(mesh.triangle_count())) : nullptr;
    j["max_error"] = s.max_error ? nlohmann::ordered_json(*s.max_error) : nullptr;
    j["output_vertices"] = r.mesh.vertex_count();
    j["output_triangles"] = r.mesh.triangle_count();
    j["output_lines"] = r.mesh.lines.size();
    j["error"] = finite_or_null(m.error);
    j["error_kind"] = error_kind();
    j["simplifier_estimate"] = finite_or_null(r.error);
    j["stop_reason"] = to_string(r.stop_reason);
    j["stop_detail"] = r.stop_detail;
    j["simplifier_runs"] = m.simplifier_runs;
    j["measurements"] = m.measurements;
    j["time_ms"] = time_ms;
    fmt::print("{}\n", j.dump(2));
    return 0;
  }
  if (s.quiet) return 0;
  fmt::print(stderr, "{}: {} triangles, {} vertices\n", s.input, mesh.triangle_count(),
             mesh.vertex_count());
  fmt::print(stderr, "{} ({}): {} triangles, {} vertices", s.output, s.method,
             r.mesh.triangle_count(), r.mesh.vertex_count());
  if (!r.mesh.lines.empty()) fmt::print(stderr, ", {} line segments", r.mesh.lines.size());
  if (by_count) fmt::print(stderr, " (target {})", target.triangle_target(mesh.triangle_count()));
  fmt::print(stderr,
             "\n  error {:.6g} ({})\n"
             "  stopped: {}: {}\n  time {:.1f} ms ({} simplifier runs, {} measurements)\n",
             m.error, error_kind(), to_string(r.stop_reason), r.stop_detail, time_ms,
             m.simplifier_runs, m.measurements);
  return 0;
}

}  // namespace

void add_simplify_command(CLI::App& app, Runner& run) {
  auto s = std::make_shared<SimplifySettings>();
  CLI::App* cmd = app.add_subcommand(
      "simplify", "Simplify one surface (mesh file or VRML 1.0 scene flattened in world space)");
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
      "time_ms (--json) covers the simplification and its measurements, not file I/O.\n"
      "Exit codes: 0 done, 1 bad input (unreadable, empty surface), 2 bad usage.\n");
  cmd->add_option("MESH", s->input,
                  "Input: PLY, OBJ, OFF, STL (optionally .gz) or VRML 1.0 (.wrl); - = stdin")
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
  cmd->add_flag("--ascii", s->ascii, "ASCII PLY / STL (default binary)");
  cmd->add_flag("--json", s->json, "Print the JSON summary on stdout (no human text)");
  cmd->add_flag("-q,--quiet", s->quiet,
                "No summary, no reader warnings and no progress bar on stderr");
  add_expansion_options(*cmd, s->read);
  cmd->callback([s, &run] { run = [s] { return run_simplify(*s); }; });
}

}  // namespace lodforge::apps
