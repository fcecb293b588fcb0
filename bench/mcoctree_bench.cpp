// The marching-cube octree: extraction throughput at several budgets, build
// time per million input triangles beside quadric collapse and
// meshopt_simplify to 20 % (linked by bench/CMakeLists.txt when installed),
// and memory per full-resolution triangle. Input: the Stanford bunny.
//
//   mcoctree_bench [benchmark flags]
// Counters: tri_per_s (extraction), input_triangles (time / input_triangles x 1e6 =
// seconds per million input triangles), bytes_per_tri.
// Issue 6's targets: >= 100 M triangles/s, <= 2 s per M input triangles,
// <= 64 bytes per full-resolution triangle.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/simplify/quadric_collapse.h"

#ifdef LODFORGE_HAVE_MESHOPTIMIZER
#include <meshoptimizer.h>
#endif

namespace {

using namespace lodforge;

std::string bunny_path() {
  if (const char* env = std::getenv("LODFORGE_SHARED_DATA"))
    return std::string(env) + "/meshes/bun_zipper.ply";
  return (std::filesystem::path(__FILE__).parent_path() / "../../shared/data/meshes/bun_zipper.ply")
      .string();
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

void BM_McoExtract(benchmark::State& state) {
  if (!bunny()) return state.SkipWithError("bunny missing");
  const McOctree* t = model(static_cast<int>(state.range(1)));
  auto n = priority_for_triangles(
      *t, t->full_triangles() * static_cast<std::uint64_t>(state.range(0)) / 100);
  McExtractor ex(*t);
  TriangleMesh out;
  std::size_t tris = 0;
  for (auto _ : state) tris += ex.extract(n, out);
  state.counters["triangles"] = static_cast<double>(out.triangle_count());
  state.counters["tri_per_s"] =
      benchmark::Counter(static_cast<double>(tris), benchmark::Counter::kIsRate);
  state.counters["bytes_per_tri"] =
      static_cast<double>(t->memory_bytes()) / static_cast<double>(t->full_triangles());
}
BENCHMARK(BM_McoExtract)
    ->ArgsProduct({{5, 20, 50, 100}, {128}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_McoBuild(benchmark::State& state) {
  if (!bunny()) return state.SkipWithError("bunny missing");
  for (auto _ : state) {
    auto r = build_mc_octree(*bunny(), {.resolution = static_cast<int>(state.range(0))});
    benchmark::DoNotOptimize(r.tree.nodes.data());
  }
  state.counters["input_triangles"] = static_cast<double>(bunny()->triangle_count());
}
BENCHMARK(BM_McoBuild)
    ->Arg(64)
    ->Arg(128)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();

void BM_QuadricTo20(benchmark::State& state) {
  if (!bunny()) return state.SkipWithError("bunny missing");
  for (auto _ : state) {
    auto r = quadric_collapse(*bunny(), {.target = {.ratio = 0.2f}});
    benchmark::DoNotOptimize(r.mesh.triangles.data());
  }
  state.counters["input_triangles"] = static_cast<double>(bunny()->triangle_count());
}
BENCHMARK(BM_QuadricTo20)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

#ifdef LODFORGE_HAVE_MESHOPTIMIZER
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
}
BENCHMARK(BM_MeshoptSimplifyTo20)->Unit(benchmark::kMillisecond)->UseRealTime();
#endif

}  // namespace

BENCHMARK_MAIN();
