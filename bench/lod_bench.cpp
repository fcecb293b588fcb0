// The scene LOD pipeline on one scene made of the Stanford bunny and every
// file of the VRML 1.0 corpus (../shared/data), with one thread and with all
// threads, in the same run: the peer of a parallel pipeline is itself on one
// core. Shapes are independent, so the target is near-linear scaling.
//
//   build/bench/lod_bench --benchmark_min_time=1
//
// Reports real time; the ratio one-thread / all-threads is the speed-up.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <thread>

#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/lod/generate_lod.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/scene/schema.h"

namespace {

using namespace lodforge;

const std::string kData = "../shared/data";

std::string data_dir() {
  for (std::string d : {kData, "../" + kData, "../../" + kData, std::string("/work/shared/data")})
    if (std::filesystem::is_directory(d)) return d;
  return "";
}

// The bunny as an IndexedFaceSet, and every corpus scene, each under its own
// Separator of one root.
const scene::Scene& bench_scene() {
  static scene::Scene s = [] {
    scene::Scene out;
    auto root = std::make_shared<scene::Node>();
    root->type = "Separator";
    out.roots.push_back(root);
    const std::string dir = data_dir();
    if (dir.empty()) return out;
    TriangleMesh bunny = read_mesh(dir + "/meshes/bun_zipper.ply");
    auto sep = std::make_shared<scene::Node>();
    sep->type = "Separator";
    auto coords = std::make_shared<scene::Node>();
    coords->type = "Coordinate3";
    std::vector<float> pts;
    for (const auto& p : bunny.positions) pts.insert(pts.end(), {p.x, p.y, p.z});
    coords->set("point", scene::make_floats(scene::FieldKind::kVec3f, true, pts));
    auto ifs = std::make_shared<scene::Node>();
    ifs->type = "IndexedFaceSet";
    std::vector<std::int32_t> idx;
    for (const auto& t : bunny.triangles)
      idx.insert(idx.end(), {std::int32_t(t[0]), std::int32_t(t[1]), std::int32_t(t[2]), -1});
    ifs->set("coordIndex", scene::make_longs(idx));
    sep->children = {coords, ifs};
    root->children.push_back(sep);
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir + "/vrml1")) {
      std::string p = e.path().string();
      if (!e.is_regular_file() || !(p.ends_with(".wrl") || p.ends_with(".wrl.gz"))) continue;
      try {
        vrml1::ReadResult r = vrml1::read_vrml1_file(p);
        auto part = std::make_shared<scene::Node>();
        part->type = "Separator";
        part->children = r.scene.roots;
        // Keep only parts the pipeline can take (broken geometry is skipped).
        scene::Scene probe;
        probe.roots = {part};
        generate_lod(probe, {.method = SimplifyMethod::kCluster, .min_diff = 1.0f, .threads = 1});
        root->children.push_back(part);
      } catch (const std::exception&) {
      }
    }
    return out;
  }();
  return s;
}

void BM_LodBunnyAndCorpus(benchmark::State& state) {
  const scene::Scene& s = bench_scene();
  if (s.roots.empty() || s.roots[0]->children.empty()) {
    state.SkipWithError("no ../shared/data");
    return;
  }
  const int threads = int(state.range(0));
  std::size_t shapes = 0;
  for (auto _ : state) {
    LodResult r = generate_lod(s, {.threads = threads});
    shapes = r.shapes.size();
    benchmark::DoNotOptimize(r.scene.roots.data());
  }
  state.counters["shapes"] = double(shapes);
  state.counters["threads"] = threads == 0 ? double(std::thread::hardware_concurrency()) : threads;
}
BENCHMARK(BM_LodBunnyAndCorpus)
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
