// `lodforge compare A B [--json] [--samples N] [--seed S] [--threads T]
//                       [--smooth-normals] [--colored OUT.ply|OUT.png] [--color-max X]`:
// Metro-style deviation between two surfaces (the LODCreator thesis §5.2): A is
// the reference (the original), B the approximation. JSON goes to stdout with
// --json, human text to stderr otherwise.
//
// JSON keys: a, b, a_triangles, b_triangles, samples (area samples per
// direction), seed, diagonal (A's bounding box), hausdorff,
// hausdorff_pct_diag, a_to_b and b_to_a (samples measured, min, max, mean,
// rms, variance, max/mean/rms_pct_diag, normal {samples, mean, max,
// variance}, color {samples, mean, max, rms} when both have vertex colours:
// Euclidean RGB distance with channels in [0,1]), normal (= a_to_b.normal: samples on the
// reference, as in the LODCreator thesis), normals_from ("faces" or "vertices"), colored {file,
// scale_max}. Distances are in the meshes' units, angles in radians.
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <memory>
#include <nlohmann/json.hpp>

#include "lodforge/apps/commands.h"
#include "lodforge/apps/common_options.h"
#include "lodforge/apps/load_geometry.h"
#include "lodforge/core/error.h"
#include "lodforge/core/output_path.h"
#include "lodforge/core/progress.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/metrics/colorize_deviation.h"
#include "lodforge/metrics/compare_meshes.h"
#include "lodforge/render/render_mesh.h"
#include "lodforge/render/write_png.h"

namespace lodforge::apps {
namespace {

// True for a picture's name (".png", any case).
bool is_png_path(std::string path) {
  std::transform(path.begin(), path.end(), path.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return path.ends_with(".png");
}

nlohmann::ordered_json to_json(const Deviation& d) {
  nlohmann::ordered_json j;
  j["samples"] = d.samples;
  j["min"] = d.min;
  j["max"] = d.max;
  j["mean"] = d.mean;
  j["rms"] = d.rms;
  j["variance"] = d.variance;
  j["max_pct_diag"] = d.max_pct;
  j["mean_pct_diag"] = d.mean_pct;
  j["rms_pct_diag"] = d.rms_pct;
  j["normal"] = {{"samples", d.normal.samples},
                 {"mean", d.normal.mean},
                 {"max", d.normal.max},
                 {"variance", d.normal.variance}};
  if (d.color.samples) {
    j["color"] = {{"samples", d.color.samples},
                  {"mean", d.color.mean},
                  {"max", d.color.max},
                  {"rms", d.color.rms}};
  }
  return j;
}

void print_direction(const char* title, const Deviation& d) {
  fmt::print(stderr, "  {} ({} samples)\n", title, d.samples);
  fmt::print(stderr, "    max      {:.6g}  ({:.4f} % of diagonal)\n", d.max, d.max_pct);
  fmt::print(stderr, "    mean     {:.6g}  ({:.4f} %)\n", d.mean, d.mean_pct);
  fmt::print(stderr, "    rms      {:.6g}  ({:.4f} %)\n", d.rms, d.rms_pct);
  fmt::print(stderr, "    variance {:.6g}\n", d.variance);
  fmt::print(stderr, "    normal   mean {:.6g} rad, max {:.6g} rad, variance {:.6g}\n",
             d.normal.mean, d.normal.max, d.normal.variance);
  if (d.color.samples) {
    fmt::print(stderr, "    colour   mean {:.4g}, max {:.4g}, rms {:.4g} (RGB distance, 1 = 255)\n",
               d.color.mean, d.color.max, d.color.rms);
  }
}

}  // namespace

void add_compare_command(CLI::App& app, Runner& run) {
  struct Settings {
    std::string a, b;
    bool json = false;
    bool quiet = false;
    std::size_t samples = 0;
    std::uint64_t seed = 1;
    int threads = 0;
    bool smooth_normals = false;
    std::string colored;
    double color_max = 0;
    int level_a = 0, level_b = 0;
    SceneReadSettings read;
  };
  auto s = std::make_shared<Settings>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Measure the geometric and normal deviation between two surfaces (A: reference)");
  cmd->add_option("A", s->a,
                  "Reference: mesh (PLY, OBJ, OFF, STL) or scene (VRML 1.0, Inventor, VRML97, X3D "
                  "classic, glTF)")
      ->required();
  cmd->add_option("B", s->b, "Mesh or scene to measure against A")->required();
  cmd->add_option("--level", s->level_b, "LOD level of B when B is a scene (default 0)")
      ->check(kFiniteNumber)
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--level-a", s->level_a, "LOD level of A when A is a scene (default 0)")
      ->check(kFiniteNumber)
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--json", s->json, "Print JSON on stdout");
  cmd->add_flag("-q,--quiet", s->quiet, "No reader warnings and no progress bar on stderr");
  cmd->add_option("--samples", s->samples,
                  "Area samples per direction (default: 10 x the larger triangle count, "
                  "at least 100000, at most 4000000)")
      ->check(kFiniteNumber)
      ->check(CLI::PositiveNumber);
  cmd->add_option("--seed", s->seed, "Seed of the sampling (default 1)");
  cmd->add_option("--threads", s->threads, "Worker threads (default: all cores)")
      ->check(kFiniteNumber)
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--smooth-normals", s->smooth_normals,
                "Estimate missing vertex normals by averaging face normals (else face normals)");
  cmd->add_option("--colored", s->colored,
                  "Write A with per-vertex colours by deviation (blue 0, green half, red max); "
                  "a .png name gives a picture of it with the colour scale");
  cmd->add_option("--color-max", s->color_max,
                  "Deviation shown red (default: the largest vertex deviation)")
      ->check(kFiniteNumber)
      ->check(CLI::PositiveNumber);
  add_expansion_options(*cmd, s->read);
  cmd->callback([s, &run] {
    run = [s] {
      std::vector<OutputPath> outputs;
      if (!s->colored.empty()) outputs.push_back({s->colored, "the coloured mesh (--colored)"});
      if (s->json) outputs.push_back({"-", "the JSON (--json)"});
      check_output_paths(outputs, std::array{s->a, s->b});
      // Scenes are flattened in world space at the chosen LOD level.
      SceneReadSettings read = s->read;
      read.quiet = s->json || s->quiet;
      TriangleMesh a = load_geometry(s->a, s->level_a, read);
      TriangleMesh b = load_geometry(s->b, s->level_b, read);
      Progress bar("compare", 0, stderr_progress(s->quiet));
      CompareResult r = compare_meshes(a, b,
                                       {.samples = s->samples,
                                        .seed = s->seed,
                                        .threads = s->threads,
                                        .per_vertex = !s->colored.empty(),
                                        .estimate_normals = s->smooth_normals,
                                        .a_name = s->a,
                                        .b_name = s->b,
                                        .progress = bar.callback()});
      bar.finish();
      double scale_max = 0;
      if (!s->colored.empty()) {
        scale_max = s->color_max;
        if (scale_max <= 0) {
          for (float v : r.vertex_deviation) scale_max = std::max(scale_max, double(v));
        }
        a.colors = colorize_deviation(a, r.vertex_deviation, float(scale_max));
        if (is_png_path(s->colored))
          write_png(add_deviation_bar(render_mesh(a).image, scale_max), s->colored);
        else
          write_mesh(a, s->colored);
      }

      if (s->json) {
        nlohmann::ordered_json j;
        j["a"] = s->a;
        j["b"] = s->b;
        j["a_triangles"] = a.triangle_count();
        j["b_triangles"] = b.triangle_count();
        j["samples"] = r.samples;
        j["seed"] = s->seed;
        j["diagonal"] = r.diagonal;
        j["hausdorff"] = r.hausdorff;
        j["hausdorff_pct_diag"] = r.hausdorff_pct;
        j["a_to_b"] = to_json(r.a_to_b);
        j["b_to_a"] = to_json(r.b_to_a);
        // The thesis' normal deviation: samples on A (the reference) against B.
        j["normal"] = {{"mean", r.a_to_b.normal.mean},
                       {"max", r.a_to_b.normal.max},
                       {"variance", r.a_to_b.normal.variance}};
        j["normals_from"] = r.vertex_normals ? "vertices" : "faces";
        if (!s->colored.empty()) j["colored"] = {{"file", s->colored}, {"scale_max", scale_max}};
        fmt::print("{}\n", j.dump(2));
        return 0;
      }
      fmt::print(stderr, "A: {} ({} triangles)\nB: {} ({} triangles)\n", s->a, a.triangle_count(),
                 s->b, b.triangle_count());
      fmt::print(stderr, "A's bounding-box diagonal {:.6g}; {} area samples per direction\n",
                 r.diagonal, r.samples);
      print_direction("A -> B", r.a_to_b);
      print_direction("B -> A", r.b_to_a);
      fmt::print(stderr, "  Hausdorff {:.6g}  ({:.4f} % of diagonal)\n", r.hausdorff,
                 r.hausdorff_pct);
      if (!s->colored.empty()) {
        fmt::print(stderr, "coloured A written to {}: blue 0, green {:.6g}, red {:.6g}\n",
                   s->colored, scale_max / 2, scale_max);
      }
      return 0;
    };
  });
}

}  // namespace lodforge::apps
