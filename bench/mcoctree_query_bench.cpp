// Queries through the marching-cube octree (mcoctree/mc_query.h) beside
// brute force over the same level's triangles and the metrics BVH
// (metrics/triangle_bvh.h) built on that mesh, for the bunny (capped) at
// resolutions 64, 128 and 256, so that the growth with the triangle count
// shows. Rays: the first hit (octree: with its point and face normal).
// Points: the octree's closest point with its signed distance, brute
// force's closest point, the BVH's closest point; for points anywhere in
// the box and for points near the surface.
//
//   mcoctree_query_bench [benchmark flags]
// Counters: queries_per_s, triangles (of the full-resolution level), nodes
// (of the octree's search tree).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/mc_query.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/metrics/closest_point_on_triangle.h"
#include "lodforge/metrics/ray.h"
#include "lodforge/metrics/triangle_bvh.h"

#include "bench_data.h"

namespace {

using namespace lodforge;

std::string bunny_path() {
  return lodforge::bench::shared_mesh_dir() + "bun_zipper.ply";
}

// The model of the bunny at one resolution, its full-resolution query
// structure, the BVH of that level's mesh, and fixed random queries.
struct Setup {
  std::unique_ptr<McQuery> query;
  std::unique_ptr<TriangleBvh> bvh;
  std::vector<std::pair<Vec3, Vec3>> rays;  // origin, direction
  std::vector<Vec3> points;
  std::vector<Vec3> near;  // within a finest cell of the surface
};

const Setup* setup(int resolution) {
  static std::map<int, Setup> cache;
  auto it = cache.find(resolution);
  if (it != cache.end()) return &it->second;
  if (!std::filesystem::exists(bunny_path())) return nullptr;
  Setup& s = cache[resolution];
  const McLodModel model =
      compile_mc_lod(build_mc_octree(read_mesh(bunny_path()),
                                     {.resolution = resolution, .holes = McHoles::kCapped})
                         .tree);
  s.query = std::make_unique<McQuery>(model);
  s.bvh = std::make_unique<TriangleBvh>(s.query->mesh());
  // Points in the box grown by a fifth of its diagonal; rays from such
  // points, every other one aimed at a point of the box (most of those hit).
  Box3 box = s.query->mesh().bounds();
  const float g = 0.2f * box.diagonal();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0, 1);
  std::normal_distribution<float> n;
  auto in = [&](float grow) {
    Vec3 lo = box.lo - Vec3{grow, grow, grow}, hi = box.hi + Vec3{grow, grow, grow};
    return Vec3{lo.x + u(rng) * (hi.x - lo.x), lo.y + u(rng) * (hi.y - lo.y),
                lo.z + u(rng) * (hi.z - lo.z)};
  };
  for (int i = 0; i < 4096; ++i) {
    Vec3 o = in(g);
    s.rays.push_back({o, i % 2 ? in(0) - o : Vec3{n(rng), n(rng), n(rng)}});
    s.points.push_back(in(g));
  }
  const TriangleMesh& m = s.query->mesh();
  std::uniform_int_distribution<std::size_t> pick(0, m.triangles.size() - 1);
  for (int i = 0; i < 4096; ++i) {
    const auto& f = m.triangles[pick(rng)];
    const Vec3 &a = m.positions[f[0]], &b = m.positions[f[1]], &c = m.positions[f[2]];
    float x = u(rng), y = u(rng);
    if (x + y > 1) x = 1 - x, y = 1 - y;
    const Vec3 normal = normalized(cross(b - a, c - a));
    s.near.push_back(a + (b - a) * x + (c - a) * y + normal * ((2 * u(rng) - 1) * model.cell_size));
  }
  return &s;
}

enum Method { kOctree, kBrute, kBvh };

void counters(benchmark::State& state, const Setup& s, std::size_t queries) {
  state.counters["queries_per_s"] =
      benchmark::Counter(static_cast<double>(queries), benchmark::Counter::kIsRate);
  state.counters["triangles"] = static_cast<double>(s.query->mesh().triangle_count());
  state.counters["nodes"] = static_cast<double>(s.query->node_count());
}

// Brute force's first hit: every triangle tested (metrics/ray.h).
float brute_ray(const TriangleMesh& m, Vec3 o, Vec3 d) {
  const Ray ray(o, normalized(d));
  double best = -1;
  for (const auto& f : m.triangles)
    if (double t = ray.hit(m.positions[f[0]], m.positions[f[1]], m.positions[f[2]]);
        t >= 0 && (best < 0 || t < best))
      best = t;
  return static_cast<float>(best);
}

// Args: resolution, method (0 octree, 1 brute force, 2 BVH).
void BM_McoQueryRay(benchmark::State& state) {
  const Setup* s = setup(static_cast<int>(state.range(0)));
  if (!s) return state.SkipWithError("bunny missing");
  const auto method = static_cast<Method>(state.range(1));
  // Brute force takes milliseconds per query at 256: a subset.
  const std::size_t count = method == kBrute ? 64 : s->rays.size();
  std::size_t done = 0;
  for (auto _ : state) {
    for (std::size_t i = 0; i < count; ++i) {
      const auto& [o, d] = s->rays[i];
      if (method == kOctree)
        benchmark::DoNotOptimize(s->query->ray(o, d));
      else if (method == kBvh)
        benchmark::DoNotOptimize(s->bvh->first_hit(o, d));
      else
        benchmark::DoNotOptimize(brute_ray(s->query->mesh(), o, d));
    }
    done += count;
  }
  counters(state, *s, done);
}
BENCHMARK(BM_McoQueryRay)
    ->ArgsProduct({{64, 128, 256}, {kOctree, kBrute, kBvh}})
    ->Unit(benchmark::kMicrosecond);

// Args: resolution, method (0 octree, 1 brute force, 2 BVH), points (0: in
// the box grown by a fifth of its diagonal, 1: within a finest cell of the
// surface). A point at distance D visits the cells whose boxes are nearer
// than D, a number that grows with D over the cell size: about linearly
// in the resolution for the points of the box, with log n for those near
// the surface.
void BM_McoQueryPoint(benchmark::State& state) {
  const Setup* s = setup(static_cast<int>(state.range(0)));
  if (!s) return state.SkipWithError("bunny missing");
  const auto method = static_cast<Method>(state.range(1));
  const std::vector<Vec3>& points = state.range(2) ? s->near : s->points;
  const std::size_t count = method == kBrute ? 64 : points.size();
  const TriangleMesh& m = s->query->mesh();
  std::size_t done = 0;
  for (auto _ : state) {
    for (std::size_t i = 0; i < count; ++i) {
      const Vec3 p = points[i];
      if (method == kOctree) {
        benchmark::DoNotOptimize(s->query->closest(p));
      } else if (method == kBvh) {
        benchmark::DoNotOptimize(s->bvh->closest_point(p));
      } else {
        float best = std::numeric_limits<float>::infinity();
        for (const auto& f : m.triangles)
          best = std::min(best, closest_point_on_triangle(p, m.positions[f[0]], m.positions[f[1]],
                                                          m.positions[f[2]])
                                    .distance_squared);
        benchmark::DoNotOptimize(best);
      }
    }
    done += count;
  }
  counters(state, *s, done);
}
BENCHMARK(BM_McoQueryPoint)
    ->ArgsProduct({{64, 128, 256}, {kOctree, kBrute, kBvh}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
