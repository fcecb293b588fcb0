// Bridges keep a closed mesh's parts whole where they are thinner than a
// cell: built models of a pinched torus and of the shared closed meshes.
#include "lodforge/mcoctree/part_bridges.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "lodforge/mcoctree/mc_parts.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/metrics/compare_meshes.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

// A torus (R = 1, r = 0.3) pinched to a tube of radius 0.015 at two opposite
// places (x = +-1, y = 0), the pinches raised by 0.05: at resolution 26 (a
// cell of 0.1, lattice points at z = 0 +- k cells) no lattice point falls
// inside them, and the ring comes apart into two halves.
TriangleMesh make_pinched_torus(Vec3 offset = {}) {
  TriangleMesh m = test::make_torus(1.0f, 0.3f, 96, 24);
  for (Vec3& p : m.positions) {
    const float u = std::atan2(p.y, p.x), ring = std::hypot(p.x, p.y);
    const float squeeze = std::max(0.05f, std::abs(std::sin(u)));
    const float w = 1 + (ring - 1) * squeeze;
    p = Vec3{w * std::cos(u), w * std::sin(u), p.z * squeeze + 0.05f * (1 - squeeze)} + offset;
  }
  return m;
}

struct Built {
  McBuildStats stats;
  TriangleMesh full;
  McPartsCheck parts;
};

Built build_full(const TriangleMesh& mesh, int resolution = 0) {
  McBuildResult r = build_mc_octree(mesh, {.resolution = resolution});
  TriangleMesh full = extract_mc_mesh(r.tree).mesh;
  McPartsCheck parts = check_mc_parts(mesh, full);
  return {r.stats, std::move(full), std::move(parts)};
}

TEST(BridgeMeshParts, PinchedTorusStaysOneRing) {
  const TriangleMesh torus = make_pinched_torus();
  const Built b = build_full(torus, 26);
  EXPECT_TRUE(b.parts.kept()) << b.parts.model_parts << " parts";
  EXPECT_GE(b.stats.part_bridges, 1u);
  // The bridges hug the pinches: the model stays within about a cell of the
  // input (one way: the pinches themselves are thinner than the model).
  const float cell = 2.6f / 26;
  const CompareResult c = compare_meshes(torus, b.full, {.samples = 20000, .per_vertex = false});
  EXPECT_LE(c.b_to_a.max, 1.5f * cell);
}

// Two parts of the input stay two: a bridge joins pieces of one part only.
TEST(BridgeMeshParts, SeparatePartsStaySeparate) {
  TriangleMesh two = make_pinched_torus();
  const TriangleMesh other = make_pinched_torus({0, 0, 1});
  const auto base = static_cast<std::uint32_t>(two.positions.size());
  two.positions.insert(two.positions.end(), other.positions.begin(), other.positions.end());
  for (Triangle t : other.triangles)
    two.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  const Built b = build_full(two, 26);
  EXPECT_EQ(b.parts.input_parts, 2u);
  EXPECT_EQ(b.parts.model_parts, 2u);
}

// Every closed mesh of the shared data keeps its parts at the default
// resolution (without the bridges: cow 10 parts, horse 2).
TEST(BridgeMeshParts, SharedClosedMeshesKeepTheirParts) {
  for (const char* name :
       {"cow.obj", "horse.ply", "fandisk.obj", "rocker-arm.obj", "nefertiti.obj", "igea.ply"}) {
    const std::string path = std::string(LODFORGE_SHARED_DATA) + "/meshes/" + name;
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " missing";
    const Built b = build_full(read_mesh(path));
    EXPECT_TRUE(b.parts.kept()) << name << ": " << b.parts.model_parts << " parts, input "
                                << b.parts.input_parts;
    std::printf("%s: resolution %d, %zu parts, %zu bridges\n", name, b.stats.resolution,
                b.parts.model_parts, b.stats.part_bridges);
  }
}

}  // namespace
}  // namespace lodforge
