#include "lodforge/mcoctree/scan_mesh.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "lodforge/core/error.h"
#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "lodforge/metrics/compare_meshes.h"
#include "mcoctree/crack_check.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

TEST(ScanMesh, PointsLieOnTheSphereAndFaceTheSensor) {
  auto sphere = test::make_icosphere(3);
  auto scans = scan_mesh(sphere, {.views = 4, .resolution = 32});
  ASSERT_EQ(scans.size(), 4u);
  for (const auto& s : scans) {
    EXPECT_EQ(s.grid.size(), 32u * 32u);
    EXPECT_GT(s.points.size(), 250u);  // the disc covers pi / 12 of the square (radius sqrt 3)
    auto normals = s.normals();
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      Vec3 w = s.to_world(s.points[i]);
      EXPECT_NEAR(length(w), 1.0f, 0.02f);
      // Normals in world: outward wherever the grid is not grazing.
      Vec3 n = s.rotate(normals[i]);
      EXPECT_GT(dot(n, w), -0.2f);
    }
  }
}

// Scans of a closed mesh from several views, built back: the surface is close
// to the original both ways.
void expect_round_trip(const TriangleMesh& mesh, int views, int scan_res, int res,
                       double max_mean_pct, double max_max_pct) {
  auto scans = scan_mesh(mesh, {.views = views, .resolution = scan_res});
  auto r = build_mc_octree(scans, {.resolution = res, .threads = 2});
  auto full = extract_mc_mesh(r.tree).mesh;
  auto c = compare_meshes(mesh, full, {.samples = 20000, .threads = 2, .per_vertex = false});
  EXPECT_LT(c.a_to_b.mean_pct, max_mean_pct);
  EXPECT_LT(c.a_to_b.max_pct, max_max_pct);
  // Back from ours to the original: regions no view saw (the torus's inner
  // rim between views) are closed where the inside and outside floods meet,
  // farther off; the mean stays small.
  EXPECT_LT(c.b_to_a.mean_pct, 2 * max_mean_pct);
  // And crack-free at a coarser level.
  auto half = extract_mc_mesh(r.tree, {.percent = 50}).mesh;
  auto report = test::crack_report(half);
  EXPECT_TRUE(report.ok()) << "scans at 50 %: " << report.describe();
}

TEST(ScanMesh, SphereFromSixViews) {
  expect_round_trip(test::make_icosphere(3), 6, 64, 24, 0.3, 2);
}

TEST(ScanMesh, TorusFromEightViews) {
  expect_round_trip(test::make_torus(1.0f, 0.35f, 48, 24), 8, 96, 32, 0.3, 2);
}

TEST(ScanMesh, ColoursAreCarried) {
  auto sphere = test::make_icosphere(2);
  sphere.colors.resize(sphere.positions.size());
  for (std::size_t v = 0; v < sphere.positions.size(); ++v)
    sphere.colors[v] = sphere.positions[v].x > 0 ? Vec3{1, 0, 0} : Vec3{0, 0, 1};
  auto scans = scan_mesh(sphere, {.views = 6, .resolution = 48});
  for (const auto& s : scans) ASSERT_EQ(s.colors.size(), s.points.size());
  auto t = build_mc_octree(scans, {.resolution = 16, .threads = 2}).tree;
  ASSERT_EQ(t.colors.size(), t.positions.size());
  int right = 0;
  for (std::size_t v = 0; v < t.positions.size(); ++v)
    if (std::abs(t.positions[v].x) > 0.3f)
      right += (t.positions[v].x > 0) == (t.colors[v][0] > t.colors[v][2]);
  int far = 0;
  for (const auto& p : t.positions) far += std::abs(p.x) > 0.3f;
  EXPECT_EQ(right, far);
}

TEST(ScanMesh, BadInput) {
  EXPECT_THROW(scan_mesh(TriangleMesh{}), DataError);
  EXPECT_THROW(scan_mesh(test::make_tetrahedron(), {.views = 0}), DataError);
  EXPECT_THROW(build_mc_octree(std::vector<RangeScan>{}), DataError);
  RangeScan empty;
  empty.cols = empty.rows = 2;
  empty.grid.assign(4, -1);
  EXPECT_THROW(build_mc_octree(std::vector<RangeScan>{empty}), DataError);
}

}  // namespace
}  // namespace lodforge
