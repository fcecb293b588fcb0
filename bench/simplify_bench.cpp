// The three simplifiers side by side with their peers, in one run (issue 4's
// benchmark): the Stanford bunny (bun_zipper.ply, 69 451 triangles) and the
// largest mesh of the corpus (igea.ply, 268 686 triangles) at 50 % and 99 %
// reduction, and vertex clustering's whole chain.
//
// clang-format off
// | row                    | what is timed                                  | peer (ratio = time / peer's)     |
// |------------------------|------------------------------------------------|----------------------------------|
// | meshopt_simplify       | meshopt_simplify to the target count           | -                                |
// | qem                    | quadric_collapse to the target count           | meshopt_simplify, same target    |
// | decimate               | vertex_decimation to the target count          | qem, same target                 |
// | meshopt_simplifySloppy | meshopt_simplifySloppy to the cluster row's    | -                                |
// |                        | count                                          |                                  |
// | cluster                | vertex_clustering, the chain up to its first   | meshopt_simplifySloppy, same     |
// |                        | level at or below the target count             | count                            |
// | cluster chain          | vertex_clustering, the whole chain             | meshopt_simplifySloppy to the    |
// |                        |                                                | chain's lowest level             |
// clang-format on
//
// Issue 4's targets: qem <= 1.5x meshopt_simplify, cluster chain <= 3x
// meshopt_simplifySloppy, decimate <= 3x qem. Peers run before the rows that
// compare with them, so that each row's ratio counters are known when it is
// reported. Counters: `triangles` (the count reached), `peer_ratio` (wall
// time / the peer's; the benchmark's reported time is this wall time) and
// `peer_ratio_cpu` (process CPU time of all threads / the peer's). The
// clustering is multi-threaded (its wall time is below its CPU time); the
// others run on one thread, so on a loaded machine their CPU ratio is the
// steadier figure.
//
// After the timed runs, an untimed step measures every row's output against
// its input with compare_meshes (default sampling): "mean" is the larger of
// the two one-sided mean deviations, "max" the Hausdorff distance, in model
// units. The table is printed on stdout as Markdown and, with
// --markdown=FILE, also written there.
//
//   simplify_bench [--markdown=FILE] [--no-quality] [benchmark flags]
// Without meshoptimizer in the build (bench/CMakeLists.txt links it when
// installed) the meshopt rows are missing and qem/cluster have no ratio.
#include <benchmark/benchmark.h>
#include <fmt/core.h>

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "lodforge/mesh/mesh_io.h"
#include "lodforge/metrics/compare_meshes.h"
#include "lodforge/simplify/quadric_collapse.h"
#include "lodforge/simplify/vertex_clustering.h"
#include "lodforge/simplify/vertex_decimation.h"

#ifdef LODFORGE_HAVE_MESHOPTIMIZER
#include <meshoptimizer.h>
#endif

#include "bench_data.h"

namespace {

using namespace lodforge;
using Clock = std::chrono::steady_clock;

std::string mesh_dir() {
  return lodforge::bench::shared_mesh_dir();
}

/// One row of the table: filled by its benchmark (time, output), then by the
/// quality step.
struct Row {
  std::string method;
  std::string mesh;
  std::string reduction;  ///< "50 %", "99 %" or "chain"
  const TriangleMesh* input = nullptr;
  std::size_t target = 0;  ///< triangle count asked for (0: whole chain)
  std::string peer;        ///< key of the peer row, empty if none
  double ms = 0;           ///< wall time per run
  double cpu_ms = 0;       ///< process CPU time per run (all threads)
  TriangleMesh output;     ///< the last run's result
  double mean = -1, max = -1;
  std::string key() const { return method + " " + mesh + " " + reduction; }
};

std::vector<Row> g_rows;  // in run order
std::map<std::string, std::size_t> g_index;

Row& row(const std::string& key) {
  return g_rows[g_index.at(key)];
}

/// CPU time of the whole process (every thread), in milliseconds.
double process_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

/// Runs the row's simplifier in the benchmark loop, timing each run by wall
/// clock (manual time), and records the row's time, output and counters.
void run_row(benchmark::State& state, std::size_t index,
             const std::function<TriangleMesh(const Row&)>& simplify) {
  Row& r = g_rows[index];
  TriangleMesh out;
  double total_ms = 0, total_cpu_ms = 0;
  for (auto _ : state) {
    auto start = Clock::now();
    double cpu_start = process_cpu_ms();
    out = simplify(r);
    double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    total_cpu_ms += process_cpu_ms() - cpu_start;
    state.SetIterationTime(ms / 1000);
    total_ms += ms;
    benchmark::DoNotOptimize(out.triangles.data());
  }
  r.ms = total_ms / double(state.iterations());
  r.cpu_ms = total_cpu_ms / double(state.iterations());
  r.output = std::move(out);
  state.counters["triangles"] = double(r.output.triangle_count());
  if (!r.peer.empty() && g_index.count(r.peer) && row(r.peer).ms > 0) {
    state.counters["peer_ratio"] = r.ms / row(r.peer).ms;
    state.counters["peer_ratio_cpu"] = r.cpu_ms / row(r.peer).cpu_ms;
  }
  state.SetLabel(r.peer.empty() ? r.key() : r.key() + " / " + r.peer);
}

void register_row(Row r, const std::function<TriangleMesh(const Row&)>& simplify) {
  std::size_t i = g_rows.size();
  g_index[r.key()] = i;
  g_rows.push_back(std::move(r));
  std::string name = "BM_Simplify/" + g_rows[i].key();
  std::replace(name.begin(), name.end(), ' ', '_');
  benchmark::RegisterBenchmark(
      name.c_str(), [i, simplify](benchmark::State& state) { run_row(state, i, simplify); })
      ->Unit(benchmark::kMillisecond)
      ->UseManualTime();
}

TriangleMesh run_qem(const Row& r) {
  return quadric_collapse(*r.input, {.target = {.triangles = r.target}}).mesh;
}

TriangleMesh run_decimate(const Row& r) {
  return vertex_decimation(*r.input, {.target = {.triangles = r.target}}).mesh;
}

/// The chain up to its first level at or below the target (0: the whole
/// chain); the answer is its last level.
TriangleMesh run_cluster(const Row& r) {
  std::vector<SimplifyResult> chain =
      vertex_clustering(*r.input, {.target = {.triangles = r.target}});
  if (r.target > 0) return std::move(chain.back().mesh);
  // Whole chain: report the lowest level that still has triangles (the last
  // ones may be lines only), the level the peer is asked for.
  for (auto it = chain.rbegin(); it != chain.rend(); ++it)
    if (it->mesh.triangle_count() > 0) return std::move(it->mesh);
  return std::move(chain.front().mesh);
}

#ifdef LODFORGE_HAVE_MESHOPTIMIZER
/// The meshopt peers' outputs index the input's vertex buffer: keep only the
/// vertices used, so that the quality step does not sample unused ones.
TriangleMesh compact(const TriangleMesh& input, const std::vector<unsigned>& indices,
                     std::size_t count) {
  TriangleMesh m;
  std::vector<std::uint32_t> remap(input.vertex_count(), UINT32_MAX);
  for (std::size_t i = 0; i + 2 < count; i += 3) {
    Triangle t;
    for (int k = 0; k < 3; ++k) {
      std::uint32_t& r = remap[indices[i + k]];
      if (r == UINT32_MAX) {
        r = std::uint32_t(m.positions.size());
        m.positions.push_back(input.positions[indices[i + k]]);
      }
      t[k] = r;
    }
    m.triangles.push_back(t);
  }
  return m;
}

std::vector<unsigned> flat_indices(const TriangleMesh& m) {
  std::vector<unsigned> indices;
  indices.reserve(m.triangle_count() * 3);
  for (const Triangle& t : m.triangles) indices.insert(indices.end(), t.begin(), t.end());
  return indices;
}

template <bool kSloppy>
TriangleMesh run_meshopt(const Row& r) {
  static std::map<const TriangleMesh*, std::vector<unsigned>> indices_of;
  auto it = indices_of.find(r.input);
  if (it == indices_of.end()) it = indices_of.emplace(r.input, flat_indices(*r.input)).first;
  const std::vector<unsigned>& indices = it->second;
  std::vector<unsigned> out(indices.size());
  const float* xyz = &r.input->positions[0].x;
  std::size_t n;
  if constexpr (kSloppy)
    n = meshopt_simplifySloppy(out.data(), indices.data(), indices.size(), xyz,
                               r.input->vertex_count(), sizeof(Vec3), r.target * 3, FLT_MAX,
                               nullptr);
  else
    n = meshopt_simplify(out.data(), indices.data(), indices.size(), xyz, r.input->vertex_count(),
                         sizeof(Vec3), r.target * 3, FLT_MAX, 0, nullptr);
  return compact(*r.input, out, n);
}
#endif

/// The triangle count of the clustering's answer for a target (untimed, to
/// aim the sloppy peer at the same count).
std::size_t cluster_count(const TriangleMesh& mesh, std::size_t target) {
  return run_cluster({.input = &mesh, .target = target}).triangle_count();
}

void register_rows(const std::map<std::string, TriangleMesh>& meshes) {
  constexpr const char* kSimplify = "meshopt_simplify";
  constexpr const char* kSloppy = "meshopt_simplifySloppy";
  for (const auto& entry : meshes) {
    const std::string& name = entry.first;  // (not a structured binding: the lambda below uses it)
    const TriangleMesh& mesh = entry.second;
    for (int reduction : {50, 99}) {
      const std::size_t target = mesh.triangle_count() * std::size_t(100 - reduction) / 100;
      const std::string red = fmt::format("{} %", reduction);
      auto key = [&](const char* method) { return fmt::format("{} {} {}", method, name, red); };
      [[maybe_unused]] const std::size_t clustered = cluster_count(mesh, target);
#ifdef LODFORGE_HAVE_MESHOPTIMIZER
      register_row({kSimplify, name, red, &mesh, target}, run_meshopt<false>);
      register_row({kSloppy, name, red, &mesh, clustered}, run_meshopt<true>);
#endif
      register_row({"qem", name, red, &mesh, target, key(kSimplify)}, run_qem);
      register_row({"decimate", name, red, &mesh, target, key("qem")}, run_decimate);
      register_row({"cluster", name, red, &mesh, target, key(kSloppy)}, run_cluster);
    }
    [[maybe_unused]] const std::size_t lowest = cluster_count(mesh, 0);
#ifdef LODFORGE_HAVE_MESHOPTIMIZER
    register_row({kSloppy, name, "chain", &mesh, lowest}, run_meshopt<true>);
#endif
    register_row({"cluster", name, "chain", &mesh, 0, std::string(kSloppy) + " " + name + " chain"},
                 run_cluster);
  }
}

/// The untimed quality step: every row's output against its input.
void measure_quality() {
  for (Row& r : g_rows) {
    if (r.ms == 0 || r.output.triangle_count() == 0) continue;  // not run, or nothing to measure
    CompareResult c = compare_meshes(*r.input, r.output, {.per_vertex = false});
    r.mean = std::max(c.a_to_b.mean, c.b_to_a.mean);
    r.max = c.hausdorff;
  }
}

std::string markdown_table() {
  std::string s =
      "| method | mesh | reduction | triangles | mean dev. | max dev. (Hausdorff) | wall (ms) | "
      "CPU (ms) | ratio to peer, wall / CPU |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : g_rows) {
    if (r.ms == 0) continue;  // filtered out
    std::string ratio = "–";
    if (!r.peer.empty() && g_index.count(r.peer) && row(r.peer).ms > 0)
      ratio = fmt::format("{:.2f} / {:.2f} × {}", r.ms / row(r.peer).ms,
                          r.cpu_ms / row(r.peer).cpu_ms, row(r.peer).method);
    auto dev = [](double v) { return v < 0 ? std::string("–") : fmt::format("{:.3e}", v); };
    s += fmt::format("| {} | {} | {} | {} | {} | {} | {:.1f} | {:.1f} | {} |\n", r.method, r.mesh,
                     r.reduction, r.output.triangle_count(), dev(r.mean), dev(r.max), r.ms,
                     r.cpu_ms, ratio);
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  // Our own flags first; the rest goes to Google Benchmark.
  std::string markdown;
  bool quality = true;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    std::string a = argv[i];
    if (a.rfind("--markdown=", 0) == 0)
      markdown = a.substr(11);
    else if (a == "--no-quality")
      quality = false;
    else
      args.push_back(argv[i]);
  }
  int n = int(args.size());
  benchmark::Initialize(&n, args.data());
  if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 1;

  std::map<std::string, TriangleMesh> meshes;
  for (const char* name : {"bun_zipper.ply", "igea.ply"}) {
    std::string path = mesh_dir() + name;
    if (!std::filesystem::exists(path)) {
      fmt::print(stderr, "{} not found (set LODFORGE_SHARED_DATA)\n", path);
      return 1;
    }
    meshes.emplace(name, read_mesh(path));
  }
  register_rows(meshes);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();

  if (quality) measure_quality();
  std::string table = markdown_table();
  fmt::print("\n{}", table);
  if (!markdown.empty()) std::ofstream(markdown) << table;
  return 0;
}
