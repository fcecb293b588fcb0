// Vertex decimation throughput: the Stanford bunny (69 451 triangles) and the
// largest mesh of the shared corpus (igea.ply, 268 686 triangles) at 50 % and
// 99 % reduction, and the bunny's whole chain of 10 % steps.
//
// Peers, in the same run: quadric edge collapse on the same input and target
// (the target is "within 3x of quadric collapse"), when it is in the build,
// and meshopt_simplify when bench/CMakeLists.txt links meshoptimizer into this
// benchmark and defines LODFORGE_HAVE_MESHOPTIMIZER.
//
//   vertex_decimation_bench [benchmark flags]
// Counters: triangles = output triangle count.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "lodforge/mesh/mesh_io.h"
#include "lodforge/simplify/vertex_decimation.h"
#ifdef LODFORGE_HAVE_MESHOPTIMIZER
#include <meshoptimizer.h>
#endif
#if __has_include("lodforge/simplify/quadric_collapse.h")
#include "lodforge/simplify/quadric_collapse.h"
#define LODFORGE_BENCH_QUADRIC 1
#endif

#include "bench_data.h"

namespace {

using namespace lodforge;

std::string mesh_dir() {
  return lodforge::bench::shared_mesh_dir();
}

const char* const kMeshes[] = {"bun_zipper.ply", "igea.ply"};

/// The mesh, read once; nullptr if the corpus is missing.
const TriangleMesh* mesh(int index) {
  static std::map<int, TriangleMesh> cache;
  auto it = cache.find(index);
  if (it == cache.end()) {
    std::string path = mesh_dir() + kMeshes[index];
    if (!std::filesystem::exists(path)) return nullptr;
    it = cache.emplace(index, read_mesh(path)).first;
  }
  return &it->second;
}

// Arguments: mesh index, reduction in percent.
void BM_VertexDecimation(benchmark::State& state) {
  const TriangleMesh* m = mesh(static_cast<int>(state.range(0)));
  if (!m) return state.SkipWithError("shared corpus missing");
  VertexDecimationOptions options{.target = {.ratio = float(100 - state.range(1)) / 100}};
  std::size_t triangles = 0;
  for (auto _ : state) triangles = vertex_decimation(*m, options).mesh.triangle_count();
  state.SetLabel(kMeshes[state.range(0)]);
  state.counters["triangles"] = double(triangles);
}
BENCHMARK(BM_VertexDecimation)
    ->ArgsProduct({{0, 1}, {50, 99}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_VertexDecimationChain(benchmark::State& state) {
  const TriangleMesh* m = mesh(0);
  if (!m) return state.SkipWithError("shared corpus missing");
  std::size_t levels = 0;
  for (auto _ : state) levels = vertex_decimation_chain(*m).size();
  state.counters["levels"] = double(levels);
}
BENCHMARK(BM_VertexDecimationChain)->Unit(benchmark::kMillisecond)->UseRealTime();

#ifdef LODFORGE_BENCH_QUADRIC
void BM_QuadricCollapse(benchmark::State& state) {
  const TriangleMesh* m = mesh(static_cast<int>(state.range(0)));
  if (!m) return state.SkipWithError("shared corpus missing");
  QuadricCollapseOptions options;
  options.target.ratio = float(100 - state.range(1)) / 100;
  std::size_t triangles = 0;
  for (auto _ : state) triangles = quadric_collapse(*m, options).mesh.triangle_count();
  state.SetLabel(kMeshes[state.range(0)]);
  state.counters["triangles"] = double(triangles);
}
BENCHMARK(BM_QuadricCollapse)
    ->ArgsProduct({{0, 1}, {50, 99}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
#endif

#ifdef LODFORGE_HAVE_MESHOPTIMIZER
void BM_MeshoptSimplify(benchmark::State& state) {
  const TriangleMesh* m = mesh(static_cast<int>(state.range(0)));
  if (!m) return state.SkipWithError("shared corpus missing");
  std::vector<unsigned> indices;
  for (const Triangle& t : m->triangles) indices.insert(indices.end(), t.begin(), t.end());
  std::vector<unsigned> out(indices.size());
  std::size_t target = indices.size() * std::size_t(100 - state.range(1)) / 100 / 3 * 3;
  std::size_t count = 0;
  for (auto _ : state)
    count = meshopt_simplify(out.data(), indices.data(), indices.size(), &m->positions[0].x,
                             m->vertex_count(), sizeof(Vec3), target, 1e30f, 0, nullptr);
  state.SetLabel(kMeshes[state.range(0)]);
  state.counters["triangles"] = double(count / 3);
}
BENCHMARK(BM_MeshoptSimplify)
    ->ArgsProduct({{0, 1}, {50, 99}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
#endif

}  // namespace

BENCHMARK_MAIN();
