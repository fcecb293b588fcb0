// `compare` throughput: the Stanford bunny (69 451 triangles) against
// Stanford's own 16 301-triangle version (bun_zipper_res2.ply), 1 million
// area samples each way plus every vertex, as `lodforge compare` runs it.
//
// Peer, in the same run: the brute-force closest point (every triangle for
// every query) on a subset of the same queries, which is what the BVH must
// agree with and what it is there to beat. (CGAL's AABB tree would be the
// natural library peer; it is not installed on the project's machines, and
// the BVH's throughput — see BM_BvhQueries — is what the target needs.)
//
//   compare_bench [benchmark flags]
// Counters: samples/s = samples measured (both directions) per second of
// wall time; queries/s for the query-only benchmarks.
#include <benchmark/benchmark.h>
#include <tbb/parallel_for.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "lodforge/mesh/mesh_io.h"
#include "lodforge/metrics/closest_point_on_triangle.h"
#include "lodforge/metrics/compare_meshes.h"
#include "lodforge/metrics/sample_surface.h"
#include "lodforge/metrics/triangle_bvh.h"

#include "bench_data.h"

namespace {

using namespace lodforge;

std::string mesh_dir() {
  return lodforge::bench::shared_mesh_dir();
}

struct Meshes {
  TriangleMesh full, low;
  bool ok = false;
};

const Meshes& meshes() {
  static const Meshes m = [] {
    Meshes out;
    const std::string dir = mesh_dir();
    if (std::filesystem::exists(dir + "bun_zipper.ply") &&
        std::filesystem::exists(dir + "bun_zipper_res2.ply")) {
      out.full = read_mesh(dir + "bun_zipper.ply");
      out.low = read_mesh(dir + "bun_zipper_res2.ply");
      out.ok = true;
    }
    return out;
  }();
  return m;
}

void BM_CompareBunny(benchmark::State& state) {
  const Meshes& m = meshes();
  if (!m.ok) return state.SkipWithError("Stanford bunny not found (set LODFORGE_SHARED_DATA)");
  std::size_t samples = 0;
  for (auto _ : state) {
    CompareResult r = compare_meshes(m.full, m.low, {.samples = 1'000'000});
    samples += r.a_to_b.samples + r.b_to_a.samples;
    benchmark::DoNotOptimize(r.hausdorff);
    state.counters["hausdorff_pct"] = r.hausdorff_pct;
    state.counters["mean_ab_pct"] = r.a_to_b.mean_pct;
  }
  state.counters["samples/s"] = benchmark::Counter(double(samples), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_CompareBunny)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

void BM_BvhBuild(benchmark::State& state) {
  const Meshes& m = meshes();
  if (!m.ok) return state.SkipWithError("Stanford bunny not found");
  for (auto _ : state) {
    TriangleBvh bvh(m.full);
    benchmark::DoNotOptimize(bvh.node_count());
  }
}
BENCHMARK(BM_BvhBuild)->Unit(benchmark::kMillisecond)->UseRealTime();

// Samples on the low-resolution bunny against the full one: the expensive
// direction. Arg 0: plain queries; 1: with the normal tie rule; 2: tie rule
// and the previous answer as a hint within blocks of 256, as compare runs.
void BM_BvhQueries(benchmark::State& state) {
  const Meshes& m = meshes();
  if (!m.ok) return state.SkipWithError("Stanford bunny not found");
  TriangleBvh bvh(m.full);
  SurfaceSamples s = sample_surface(m.low, {.count = 1'000'000, .vertices = false});
  const int mode = int(state.range(0));
  std::size_t queries = 0;
  for (auto _ : state) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, s.size(), 256), [&](const auto& r) {
      std::uint32_t hint = ClosestPoint::kNone;
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        ClosestPoint c = mode == 0 ? bvh.closest_point(s.positions[i])
                                   : bvh.closest_point(s.positions[i], s.normals[i], hint);
        if (mode == 2) hint = c.triangle;
        benchmark::DoNotOptimize(c.distance_squared);
      }
    });
    queries += s.size();
  }
  state.counters["queries/s"] = benchmark::Counter(double(queries), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BvhQueries)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The peer: brute force over all 69 451 triangles, on 2 000 of the queries.
void BM_BruteForceQueries(benchmark::State& state) {
  const Meshes& m = meshes();
  if (!m.ok) return state.SkipWithError("Stanford bunny not found");
  SurfaceSamples s = sample_surface(m.low, {.count = 2'000, .vertices = false});
  std::size_t queries = 0;
  for (auto _ : state) {
    tbb::parallel_for(std::size_t(0), s.size(), [&](std::size_t i) {
      float best = std::numeric_limits<float>::infinity();
      for (const auto& t : m.full.triangles) {
        best =
            std::min(best, closest_point_on_triangle(s.positions[i], m.full.positions[t[0]],
                                                     m.full.positions[t[1]], m.full.positions[t[2]])
                               .distance_squared);
      }
      benchmark::DoNotOptimize(best);
    });
    queries += s.size();
  }
  state.counters["queries/s"] = benchmark::Counter(double(queries), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BruteForceQueries)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
