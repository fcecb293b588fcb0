// `lodforge simplify MESH -o OUT (--ratio R | --triangles N) [--error E]
//                    [--method cluster|decimate|qem] [--format F] [--ascii] [--json]`:
// simplifies one surface (SPEC §3, §6; issue 4 item 6) with one of the three
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
// Methods and what "error" means (each is what the simplifier reports, in
// model units; see the simplifiers' headers):
//
// | method   | function                 | count target              | error            |
// |----------|--------------------------|---------------------------|------------------|
// | qem      | quadric_collapse         | met exactly or just below | upper bound on   |
// |          |                          |                           | one-sided        |
// |          |                          |                           | Hausdorff, result|
// |          |                          |                           | -> input         |
// | decimate | vertex_decimation        | one vertex (about two     | Schroeder's      |
// |          |                          | triangles) at a time, so  | accumulated      |
// |          |                          | at or just below; no      | error (estimate) |
// |          |                          | chain level needed        |                  |
// | cluster  | vertex_clustering chain  | the first level AT OR     | largest vertex   |
// |          |                          | BELOW the count (levels   | displacement     |
// |          |                          | fall at the octree's own  | (not Hausdorff)  |
// |          |                          | counts; the level above   |                  |
// |          |                          | would exceed the count)   |                  |
//
// Stopping short of the target (no allowed operation left) is a result, not
// an error: exit 0, the reason in stop_reason / stop_detail.
//
// JSON keys (stdout, --json): input, output, method, input_vertices,
// input_triangles, target_triangles (null with --error alone), max_error
// (null without --error), output_vertices, output_triangles, output_lines,
// error, error_kind, stop_reason, stop_detail, time_ms (the simplification
// alone: no file reading or writing; steady_clock), and for cluster `level`
// and `levels` (the chosen chain level and how many were made). JSON has no
// infinity: an error the simplifier reports as non-finite prints as null
// (vertex clustering's displacement overflows float beyond about 1e19).
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
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/simplify/quadric_collapse.h"
#include "lodforge/simplify/vertex_clustering.h"
#include "lodforge/simplify/vertex_decimation.h"

namespace lodforge::apps {
namespace {

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

/// What the method's `error` is, for the JSON and the summary.
const char* error_kind(const std::string& method) {
  if (method == "qem") return "upper bound on the one-sided Hausdorff distance, result to input";
  if (method == "decimate") return "accumulated Schroeder error (estimate)";
  return "largest vertex displacement";
}

/// The simplified mesh and what the chain said about it.
struct Outcome {
  SimplifyResult result;
  std::size_t level = 0;   ///< cluster: index of the chosen chain level
  std::size_t levels = 0;  ///< cluster: number of levels made
};

Outcome run_method(const TriangleMesh& mesh, const SimplifySettings& s,
                   const SimplifyTarget& target) {
  Outcome o;
  if (s.method == "qem") {
    o.result = quadric_collapse(mesh, {.target = target});
  } else if (s.method == "decimate") {
    o.result = vertex_decimation(mesh, {.target = target});
  } else {
    // The chain ends at the first level at or below the count, or at the last
    // level within the error budget: its last level is the answer.
    std::vector<SimplifyResult> chain = vertex_clustering(mesh, {.target = target});
    o.levels = chain.size();
    o.level = chain.size() - 1;
    o.result = std::move(chain.back());
  }
  return o;
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
  Outcome o = run_method(mesh, s, target);
  double time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const SimplifyResult& r = o.result;

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
    j["error"] = r.error;
    j["error_kind"] = error_kind(s.method);
    j["stop_reason"] = to_string(r.stop_reason);
    j["stop_detail"] = r.stop_detail;
    j["time_ms"] = time_ms;
    if (s.method == "cluster") {
      j["level"] = o.level;
      j["levels"] = o.levels;
    }
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
  if (s.method == "cluster")
    fmt::print(stderr, "; chain level {} (of levels 0-{})", o.level, o.levels - 1);
  fmt::print(stderr, "\n  error {:.6g} ({})\n  stopped: {}: {}\n  time {:.1f} ms\n", r.error,
             error_kind(s.method), to_string(r.stop_reason), r.stop_detail, time_ms);
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
      "Methods and the error they report (model units):\n"
      "  qem       quadric edge collapse (best quality); count met at or just below;\n"
      "            error = upper bound on the Hausdorff distance from the result to the input\n"
      "  decimate  vertex decimation (Schroeder); removes one vertex at a time, so the count\n"
      "            is met at or just below; error = accumulated Schroeder error (an estimate)\n"
      "  cluster   octree vertex clustering; levels fall at the octree's own counts: the\n"
      "            first level AT OR BELOW the count is written (its actual count reported);\n"
      "            error = largest vertex displacement (not a Hausdorff bound)\n"
      "time_ms (--json) covers the simplification alone, without reading or writing files.\n"
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
                  "Error budget in model units (see the methods below); alone: simplify as far "
                  "as the budget allows");
  cmd->add_option("--method", s->method, "cluster, decimate or qem (default qem)")
      ->check(CLI::IsMember({"cluster", "decimate", "qem"}));
  cmd->add_option("--format", s->format, "Output format: ply, obj, off or stl (default: extension)")
      ->check(CLI::IsMember({"ply", "obj", "off", "stl"}));
  cmd->add_flag("--ascii", s->ascii, "ASCII PLY / STL (default binary)");
  cmd->add_flag("--json", s->json, "Print the JSON summary on stdout (no human text)");
  cmd->add_flag("-q,--quiet", s->quiet, "No summary and no reader warnings on stderr");
  add_expansion_options(*cmd, s->read);
  cmd->callback([s, &run] { run = [s] { return run_simplify(*s); }; });
}

}  // namespace lodforge::apps
