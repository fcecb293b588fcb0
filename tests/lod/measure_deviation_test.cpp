#include "lodforge/lod/measure_deviation.h"

#include <gtest/gtest.h>

#include <random>

#include "lodforge/simplify/quadric_collapse.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

// The shared n x n grid over [0,1]^2 in z = 0, lifted to height z.
TriangleMesh grid(int n, float z = 0) {
  TriangleMesh m = test::make_grid(n);
  for (auto& p : m.positions) p.z = z;
  return m;
}

TriangleMesh bumpy_sphere() {
  return test::make_bumpy_sphere(5);
}

SimplifyResult simplified(const TriangleMesh& mesh, float ratio) {
  SimplifyTarget target;
  target.ratio = ratio;
  return quadric_collapse(mesh, {.target = target});
}

TEST(DeviationMeter, OffsetSheetIsItsOffset) {
  const TriangleMesh a = grid(8);
  const TriangleMesh b = grid(3, 0.25f);
  DeviationMeter meter(a);
  EXPECT_NEAR(meter.hausdorff(b), 0.25, 1e-6);
  EXPECT_NEAR(meter.distance_to_reference(b), 0.25, 1e-6);
  EXPECT_LT(meter.hausdorff(a), 1e-6);  // float rounding of points on the surface
}

// A bump in the middle of a sheet: the largest distance is at its tip,
// found by the refinement even where no sample falls on the tip.
TEST(DeviationMeter, FindsTheTipOfABump) {
  TriangleMesh bumped = grid(16);
  const std::uint32_t middle = 8 * 17 + 8;
  bumped.positions[middle].z = 0.3f;
  const TriangleMesh flat = grid(16);
  DeviationMeter meter(flat, {.samples = 500});
  EXPECT_NEAR(meter.hausdorff(bumped), 0.3, 1e-4);
  EXPECT_NEAR(meter.distance_to_reference(bumped), 0.3, 1e-4);
}

// The face map only says where searches start: the same distance with it,
// without it, and with a map that does not fit (ignored).
TEST(DeviationMeter, FaceMapChangesNothingButTheTime) {
  const TriangleMesh sphere = bumpy_sphere();
  const SimplifyResult r = simplified(sphere, 0.2f);
  ASSERT_EQ(r.face_map.size(), r.mesh.triangle_count());
  DeviationMeter meter(sphere);
  const double plain = meter.hausdorff(r.mesh);
  EXPECT_GT(plain, 0.0);
  EXPECT_EQ(meter.hausdorff(r.mesh, r.face_map), plain);
  std::vector<std::uint32_t> wrong(r.face_map.size(), std::uint32_t(sphere.triangle_count()));
  EXPECT_EQ(meter.hausdorff(r.mesh, wrong), plain);
  EXPECT_EQ(meter.hausdorff(r.mesh, std::span(r.face_map).first(1)), plain);
  EXPECT_EQ(meter.distance_to_reference(r.mesh, r.face_map), meter.distance_to_reference(r.mesh));
}

// The estimate: exact where the reference-to-level direction holds the
// answer and a thinned sample sees it (an offset sheet, a bump of the
// reference whose tip the refinement finds), blind to the other direction,
// and on a simplified surface below the full measurement, yet of its size.
TEST(DeviationMeter, EstimateIsTheReferenceSideMeasuredThinly) {
  const TriangleMesh plane = grid(16);
  const DeviationMeter flat(plane);
  EXPECT_NEAR(flat.estimate(grid(3, 0.25f)), 0.25, 1e-6);
  TriangleMesh bumped = grid(16);
  bumped.positions[8 * 17 + 8].z = 0.3f;
  EXPECT_NEAR(DeviationMeter(bumped).estimate(plane), 0.3, 1e-4);
  EXPECT_LT(flat.estimate(bumped), 0.3 * 0.9);  // the level's own bump: the other direction

  const TriangleMesh sphere = bumpy_sphere();
  const SimplifyResult r = simplified(sphere, 0.1f);
  DeviationMeter on_sphere(sphere);
  const double full = on_sphere.hausdorff(r.mesh, r.face_map);
  const double estimate = on_sphere.estimate(r.mesh);
  EXPECT_LE(estimate, full);
  EXPECT_GE(estimate, 0.5 * full);
}

// A full measurement that starts from the estimate finds the same distance
// (up to where its local searches start) and never less than the estimate;
// it finds the bump of a reference whose estimate saw only the sheet.
TEST(DeviationMeter, FullMeasurementFromAKnownDistance) {
  const TriangleMesh sphere = bumpy_sphere();
  const SimplifyResult r = simplified(sphere, 0.1f);
  DeviationMeter meter(sphere);
  const double plain = meter.hausdorff(r.mesh, r.face_map);
  const double estimate = meter.estimate(r.mesh);
  const double from_estimate = meter.hausdorff(r.mesh, r.face_map, estimate);
  EXPECT_GE(from_estimate, estimate);
  EXPECT_NEAR(from_estimate, plain, 1e-3 * plain);

  TriangleMesh bumped = grid(16);
  bumped.positions[8 * 17 + 8].z = 0.3f;
  EXPECT_NEAR(DeviationMeter(bumped, {.samples = 500}).hausdorff(grid(3, 0.f), {}, 0.01), 0.3,
              1e-4);
}

}  // namespace
}  // namespace lodforge
