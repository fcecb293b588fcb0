#include "lodforge/simplify/detail/clustering_sort.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <filesystem>

#include "lodforge/core/morton.h"
#include "lodforge/mesh/mesh_io.h"

namespace lodforge::detail::clustering {
namespace {

/// The bunny as a triangle soup (each coordinate three to seven times),
/// every tenth vertex unused.
struct Input {
  std::vector<Vec3> positions;
  Buffer<std::uint64_t> code, keys;
};

Input bunny_input() {
  const std::filesystem::path path =
      std::filesystem::path(LODFORGE_SHARED_DATA) / "meshes" / "bun_zipper.ply";
  const TriangleMesh bunny = read_mesh(path.string());
  Input in;
  for (const Triangle& t : bunny.triangles)
    for (std::uint32_t v : t) in.positions.push_back(bunny.positions[v]);
  Box3 box;
  for (const Vec3& p : in.positions) box.add(p);
  const Vec3 size = box.size();
  const double side = std::max({size.x, size.y, size.z});
  for (std::size_t v = 0; v < in.positions.size(); ++v) {
    std::uint64_t c = kUnused;
    if (v % 10 != 0) {
      c = 0;
      for (int a = 0; a < 3; ++a) {
        const double q = (in.positions[v][a] - box.lo[a]) / side * double(1u << kMaxDepth);
        c |= morton_spread(std::min(static_cast<std::uint32_t>(q), (1u << kMaxDepth) - 1))
             << (2 - a);
      }
    }
    in.code.push_back(c);
    in.keys.push_back((c == kUnused ? kUnused : c >> 31) << 32 | v);
  }
  return in;
}

/// The order of the contract, by a comparison sort.
std::vector<std::uint32_t> reference_order(const Input& in, std::size_t n) {
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(in.keys[i]);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (in.code[a] != in.code[b]) return in.code[a] < in.code[b];
    if (in.code[a] == kUnused) return a < b;
    const Vec3 &pa = in.positions[a], &pb = in.positions[b];
    if (pa.x != pb.x) return pa.x < pb.x;
    if (pa.y != pb.y) return pa.y < pb.y;
    if (pa.z != pb.z) return pa.z < pb.z;
    return a < b;
  });
  return order;
}

std::vector<std::uint32_t> sorted(const Input& in, std::size_t n) {
  Buffer<std::uint64_t> keys(in.keys.begin(), in.keys.begin() + n);
  sort_octree_order(keys, in.code, in.positions);
  std::vector<std::uint32_t> order;
  for (std::uint64_t k : keys) order.push_back(static_cast<std::uint32_t>(k));
  return order;
}

TEST(ClusteringSort, GivesTheOrderOfAComparisonSortOnSmallAndLargeArrays) {
  const Input in = bunny_input();
  ASSERT_GT(in.keys.size(), 200000u);
  // 1 000 keys: one radix sort; the whole soup: split into groups first.
  for (std::size_t n : {std::size_t(1), std::size_t(1000), in.keys.size()})
    EXPECT_EQ(sorted(in, n), reference_order(in, n)) << n << " keys";
}

TEST(ClusteringSort, OrderDoesNotDependOnTheThreadCount) {
  const Input in = bunny_input();
  const std::vector<std::uint32_t> parallel = sorted(in, in.keys.size());
  tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
  EXPECT_EQ(sorted(in, in.keys.size()), parallel);
}

}  // namespace
}  // namespace lodforge::detail::clustering
