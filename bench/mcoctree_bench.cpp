// The marching-cube octree: extraction throughput at several budgets, build
// time per million input triangles beside quadric collapse and
// meshopt_simplify to 20 % (linked by bench/CMakeLists.txt when installed),
// and memory per full-resolution triangle. Input: the Stanford bunny.
//
//   mcoctree_bench [benchmark flags]
// Counters: tri_per_s (extraction: BM_McoExtract the index
// buffer, BM_McoExtractMesh the compacted mesh), input_triangles (time /
// input_triangles x 1e6 = seconds per million input triangles), bytes_per_tri
// (the run-time model, mc_lod_model.h; BM_McoMemory beside the build-time tree).
// Issue 6's targets: >= 100 M triangles/s, <= 2 s per M input triangles,
// <= 64 bytes per full-resolution triangle.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "lodforge/mcoctree/mc_lod_model.h"
#include "lodforge/mcoctree/view_extract.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/simplify/quadric_collapse.h"

#ifdef LODFORGE_HAVE_MESHOPTIMIZER
#include <meshoptimizer.h>
#endif

#include "bench_data.h"

namespace {

using namespace lodforge;

std::string bunny_path() {
  return lodforge::bench::shared_mesh_dir() + "bun_zipper.ply";
}

const TriangleMesh* bunny() {
  static const TriangleMesh m =
      std::filesystem::exists(bunny_path()) ? read_mesh(bunny_path()) : TriangleMesh{};
  return m.triangles.empty() ? nullptr : &m;
}

const McOctree* model(int resolution) {
  static std::map<int, McOctree> cache;
  auto it = cache.find(resolution);
  if (it == cache.end())
    it =
        cache.emplace(resolution, build_mc_octree(*bunny(), {.resolution = resolution}).tree).first;
  return &it->second;
}

// The run-time model extraction reads (the tree is not needed after this).
const McLodModel* lod_model(int resolution) {
  static std::map<int, McLodModel> cache;
  auto it = cache.find(resolution);
  if (it == cache.end()) it = cache.emplace(resolution, compile_mc_lod(*model(resolution))).first;
  return &it->second;
}

// Counters shared by the extraction benchmarks: the level's triangles, the
// rate (1e9 / tri_per_s = nanoseconds per triangle) and the run-time model's
// bytes per full-resolution triangle.
void extraction_counters(benchmark::State& state, const McLodModel& m, std::size_t level_tris,
                         std::size_t total_tris) {
  state.counters["triangles"] = static_cast<double>(level_tris);
  state.counters["tri_per_s"] =
      benchmark::Counter(static_cast<double>(total_tris), benchmark::Counter::kIsRate);
  state.counters["bytes_per_tri"] =
      static_cast<double>(m.memory_bytes()) / static_cast<double>(m.full_triangles());
}

// Index-buffer extraction (what a renderer does per level: the vertex table
// is static, the level is an index buffer). Args: percent, resolution.
void BM_McoExtract(benchmark::State& state) {
  if (!bunny()) return state.SkipWithError("bunny missing");
  const McLodModel* m = lod_model(static_cast<int>(state.range(1)));
  auto n = priority_for_triangles(
      *m, m->full_triangles() * static_cast<std::uint64_t>(state.range(0)) / 100);
  std::vector<Triangle> out;
  std::size_t tris = 0;
  for (auto _ : state) {
    tris += extract_mc_indices(*m, n, out);
    benchmark::DoNotOptimize(out.data());
  }
  extraction_counters(state, *m, out.size(), tris);
}
BENCHMARK(BM_McoExtract)
    ->ArgsProduct({{5, 20, 50, 100}, {128}})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

// Extraction as a standalone mesh: the index buffer, then the used vertices
// compacted (positions, decoded normals). Args: percent, resolution.
void BM_McoExtractMesh(benchmark::State& state) {
  if (!bunny()) return state.SkipWithError("bunny missing");
  const McLodModel* m = lod_model(static_cast<int>(state.range(1)));
  auto n = priority_for_triangles(
      *m, m->full_triangles() * static_cast<std::uint64_t>(state.range(0)) / 100);
  McExtractor ex(*m);
  TriangleMesh out;
  std::size_t tris = 0;
  for (auto _ : state) tris += ex.extract(n, out);
  extraction_counters(state, *m, out.triangle_count(), tris);
}
BENCHMARK(BM_McoExtractMesh)
    ->ArgsProduct({{5, 20, 50, 100}, {128}})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

// View-dependent extraction (view_extract.h) as a standalone mesh: a camera
// three bounding-box diagonals from the bunny, a 1080-pixel-high screen,
// pixel budget = Arg 0; then uniform extraction (BM_McoUniformAtViewCount) at
// the priority nearest the same triangle count. ns_per_tri compares them;
// prepare_ms is the extractor's one-time preparation (not in the loop);
// expanded / forced: nodes expanded, of which first by a crack rule.
McViewOptions view_options(const McLodModel& m, double pixel_error) {
  Box3 box;
  for (const auto& p : m.positions) box.add(p);
  const Vec3 eye = box.center() + normalized(Vec3{0.3f, 0.2f, 1.0f}) * (3 * box.diagonal());
  return {.camera = {.position = eye, .look_at = box.center()}, .pixel_error = pixel_error};
}

void per_triangle_counters(benchmark::State& state, std::size_t level_tris, std::size_t total) {
  state.counters["triangles"] = static_cast<double>(level_tris);
  state.counters["ns_per_tri"] = benchmark::Counter(
      static_cast<double>(total), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The pixel budgets of the view-dependent rows and their uniform peers.
void pixel_budgets(benchmark::internal::Benchmark* b) {
  for (int e : {1, 2, 4, 8}) b->Arg(e);
  b->Unit(benchmark::kMicrosecond)->UseRealTime();
}

void BM_McoViewExtract(benchmark::State& state) {
  if (!bunny()) return state.SkipWithError("bunny missing");
  const McLodModel* m = lod_model(128);
  const auto t0 = std::chrono::steady_clock::now();
  McViewExtractor ex(*m);
  const double prepare =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const McViewOptions o = view_options(*m, static_cast<double>(state.range(0)));
  std::size_t tris = 0, level = 0;
  McViewResult r;
  for (auto _ : state) {
    r = ex.extract(o);
    level = r.mesh.triangle_count();
    tris += level;
  }
  per_triangle_counters(state, level, tris);
  state.counters["expanded"] = static_cast<double>(r.expanded);
  state.counters["forced"] = static_cast<double>(r.forced);
  state.counters["pixel_error"] = r.pixel_error;
  state.counters["prepare_ms"] = prepare;
  state.counters["percent"] =
      100.0 * static_cast<double>(level) / static_cast<double>(m->full_triangles());
}
BENCHMARK(BM_McoViewExtract)->Apply(pixel_budgets);

void BM_McoUniformAtViewCount(benchmark::State& state) {
  if (!bunny()) return state.SkipWithError("bunny missing");
  const McLodModel* m = lod_model(128);
  McViewExtractor view(*m);
  const std::size_t target =
      view.extract(view_options(*m, static_cast<double>(state.range(0)))).mesh.triangle_count();
  const std::uint32_t n = priority_for_triangles(*m, target);
  McExtractor ex(*m);
  TriangleMesh out;
  std::size_t tris = 0;
  for (auto _ : state) tris += ex.extract(n, out);
  per_triangle_counters(state, out.triangle_count(), tris);
}
BENCHMARK(BM_McoUniformAtViewCount)->Apply(pixel_budgets);

// Memory of the run-time model against the build-time tree, per
// full-resolution triangle (one iteration: a size, not a time).
void BM_McoMemory(benchmark::State& state) {
  if (!bunny()) return state.SkipWithError("bunny missing");
  const int resolution = static_cast<int>(state.range(0));
  const McOctree* t = model(resolution);
  const McLodModel* m = lod_model(resolution);
  for (auto _ : state) benchmark::DoNotOptimize(m->memory_bytes());
  const auto full = static_cast<double>(m->full_triangles());
  state.counters["full_triangles"] = full;
  state.counters["bytes_per_tri"] = static_cast<double>(m->memory_bytes()) / full;
  state.counters["tree_bytes_per_tri"] = static_cast<double>(t->memory_bytes()) / full;
  state.counters["stored_per_full_tri"] = static_cast<double>(m->stored_triangles()) / full;
  state.counters["intervals_per_cell"] =
      static_cast<double>(m->intervals.size() - 1) / static_cast<double>(m->cell_count());
}
BENCHMARK(BM_McoMemory)->Arg(64)->Arg(128)->Iterations(1);

// Wall seconds per iteration per million input triangles.
void seconds_per_million(benchmark::State& state) {
  state.counters["s_per_Mtri"] = benchmark::Counter(
      static_cast<double>(bunny()->triangle_count()) / 1e6,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// Build: args resolution (0: the default, about the input's triangle count),
// threads (0: all cores), holes (0: kOpen, 1: kCapped). s_per_Mtri = wall
// seconds per million input triangles (issue 6: <= 2; compare with
// BM_MeshoptSimplifyTo20's in the same run).
void BM_McoBuild(benchmark::State& state) {
  if (!bunny()) return state.SkipWithError("bunny missing");
  McBuildOptions options{.resolution = static_cast<int>(state.range(0)),
                         .threads = static_cast<int>(state.range(1)),
                         .holes = state.range(2) ? McHoles::kCapped : McHoles::kOpen};
  McBuildResult r;
  for (auto _ : state) {
    r = build_mc_octree(*bunny(), options);
    benchmark::DoNotOptimize(r.tree.nodes.data());
  }
  state.counters["input_triangles"] = static_cast<double>(bunny()->triangle_count());
  state.counters["resolution"] = r.stats.resolution;
  state.counters["full_triangles"] = static_cast<double>(r.tree.full_triangles());
  seconds_per_million(state);
}
BENCHMARK(BM_McoBuild)
    ->ArgsProduct({{0}, {1, 0}, {0, 1}})
    ->Args({128, 0, 0})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->UseRealTime();

void BM_QuadricTo20(benchmark::State& state) {
  if (!bunny()) return state.SkipWithError("bunny missing");
  for (auto _ : state) {
    auto r = quadric_collapse(*bunny(), {.target = {.ratio = 0.2f}});
    benchmark::DoNotOptimize(r.mesh.triangles.data());
  }
  state.counters["input_triangles"] = static_cast<double>(bunny()->triangle_count());
  seconds_per_million(state);
}
BENCHMARK(BM_QuadricTo20)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

#ifdef LODFORGE_HAVE_MESHOPTIMIZER
// The build and meshopt_simplify to 20 % alternately, one of each per
// iteration, the best of each kept (holes open): a ratio that survives a shared, loaded
// machine. Args: threads (0: all cores). Counters: build_s_per_Mtri,
// meshopt_s_per_Mtri, ratio.
void BM_McoBuildBesideMeshopt(benchmark::State& state) {
  if (!bunny()) return state.SkipWithError("bunny missing");
  const TriangleMesh& m = *bunny();
  std::vector<unsigned> idx;
  for (const auto& f : m.triangles) idx.insert(idx.end(), f.begin(), f.end());
  std::vector<unsigned> out(idx.size());
  using Clock = std::chrono::steady_clock;
  double build = 1e30, simplify = 1e30;
  for (auto _ : state) {
    auto t0 = Clock::now();
    auto r =
        build_mc_octree(m, {.threads = static_cast<int>(state.range(0)), .holes = McHoles::kOpen});
    benchmark::DoNotOptimize(r.tree.nodes.data());
    auto t1 = Clock::now();
    benchmark::DoNotOptimize(meshopt_simplify(out.data(), idx.data(), idx.size(), &m.positions[0].x,
                                              m.positions.size(), sizeof(Vec3), idx.size() / 5,
                                              1.0f, 0, nullptr));
    auto t2 = Clock::now();
    build = std::min(build, std::chrono::duration<double>(t1 - t0).count());
    simplify = std::min(simplify, std::chrono::duration<double>(t2 - t1).count());
  }
  const double millions = static_cast<double>(m.triangle_count()) / 1e6;
  state.counters["build_s_per_Mtri"] = build / millions;
  state.counters["meshopt_s_per_Mtri"] = simplify / millions;
  state.counters["ratio"] = build / simplify;
}
BENCHMARK(BM_McoBuildBesideMeshopt)
    ->Arg(1)
    ->Arg(0)
    ->Iterations(10)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_MeshoptSimplifyTo20(benchmark::State& state) {
  if (!bunny()) return state.SkipWithError("bunny missing");
  const TriangleMesh& m = *bunny();
  std::vector<unsigned> idx;
  for (const auto& f : m.triangles) idx.insert(idx.end(), f.begin(), f.end());
  std::vector<unsigned> out(idx.size());
  for (auto _ : state)
    benchmark::DoNotOptimize(meshopt_simplify(out.data(), idx.data(), idx.size(), &m.positions[0].x,
                                              m.positions.size(), sizeof(Vec3), idx.size() / 5,
                                              1.0f, 0, nullptr));
  state.counters["input_triangles"] = static_cast<double>(m.triangle_count());
  seconds_per_million(state);
}
BENCHMARK(BM_MeshoptSimplifyTo20)->Unit(benchmark::kMillisecond)->UseRealTime();
#endif

}  // namespace

BENCHMARK_MAIN();
