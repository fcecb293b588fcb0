#include "lodforge/mcoctree/view_extract.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "crack_check.h"
#include "lodforge/core/error.h"
#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/metrics/sample_surface.h"
#include "lodforge/metrics/triangle_bvh.h"
#include "mcoctree/capped_model.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

const std::string kBunny = std::string(LODFORGE_SHARED_DATA) + "/meshes/bun_zipper.ply";

Box3 bounds(const TriangleMesh& m) {
  Box3 b;
  for (const auto& p : m.positions) b.add(p);
  return b;
}

// A camera `sizes` bounding-box diagonals from the box centre along `from`,
// looking at the centre (or away from it).
McCamera camera_at(const Box3& box, Vec3 from, float sizes, bool look_away = false) {
  const Vec3 c = box.center(), eye = c + normalized(from) * (sizes * box.diagonal());
  return {.position = eye, .look_at = look_away ? eye + (eye - c) : c};
}

// Triangles whose centroid lies on the camera's side of the plane through the
// box centre perpendicular to the view direction, and on the other side.
std::pair<std::size_t, std::size_t> near_far(const TriangleMesh& m, const McCamera& cam,
                                             const Box3& box) {
  const Vec3 f = normalized(cam.look_at - cam.position);
  std::size_t near = 0, far = 0;
  for (const auto& t : m.triangles) {
    const Vec3 g = (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3.0f;
    (dot(g - box.center(), f) < 0 ? near : far) += 1;
  }
  return {near, far};
}

// Worst projected error of the result, measured independently of the node
// bounds: points sampled on the full-resolution mesh, each one's distance to
// the result (exact closest point) in pixels at the point's own depth, over
// the points inside the view frustum.
double measured_pixel_error(const TriangleMesh& full, const TriangleMesh& result,
                            const McViewOptions& o) {
  const McCamera& c = o.camera;
  const Vec3 f = normalized(c.look_at - c.position);
  const Vec3 r = normalized(cross(f, c.up)), u = cross(r, f);
  const double tv = std::tan(c.fov / 2), th = tv * c.aspect;
  const TriangleBvh bvh(result);
  SurfaceSamples s = sample_surface(full, {.count = 20000, .seed = 7});
  double worst = 0;
  for (const Vec3& p : s.positions) {
    const Vec3 d = p - c.position;
    const double depth = dot(d, f);
    if (depth <= 0 || std::abs(dot(d, u)) > tv * depth || std::abs(dot(d, r)) > th * depth)
      continue;
    const double dist = std::sqrt(bvh.closest_point(p).distance_squared);
    worst = std::max(worst, dist * c.pixels / (2 * tv * depth));
  }
  return worst;
}

class ViewExtractTorus : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    torus_ = new TriangleMesh(test::make_torus(1.0f, 0.35f, 96, 48));
    model_ = new McLodModel(model_of(*torus_, 96));
  }
  static void TearDownTestSuite() {
    delete model_;
    delete torus_;
  }
  static inline TriangleMesh* torus_ = nullptr;
  static inline McLodModel* model_ = nullptr;
};

// Three box sizes away, over pixel budgets from near-full to coarse: every cut
// is closed and manifold, and some are true mixtures of levels (forced
// expansions happened), so the crack rules were exercised.
TEST_F(ViewExtractTorus, CrackFreeThreeBoxSizesAway) {
  McViewExtractor ex(*model_);
  const Box3 box = bounds(*torus_);
  std::size_t mixed = 0;
  for (Vec3 dir : {Vec3{0, 0, 1}, Vec3{1, 0.5f, 0.3f}, Vec3{0.2f, 1, 0}})
    for (double e : {1.0, 4.0, 8.0, 16.0, 32.0}) {
      auto r = ex.extract({.camera = camera_at(box, dir, 3), .pixel_error = e});
      auto report = test::crack_report(r.mesh);
      EXPECT_TRUE(report.ok()) << "error " << e << ": " << report.describe();
      EXPECT_LE(r.pixel_error, e);
      mixed += r.forced > 0 && r.mesh.triangle_count() < model_->full_triangles();
    }
  EXPECT_GE(mixed, 6u);
}

// A close camera (the torus seen whole, its near side at about a third of
// the far side's depth): at least twice the triangles on the camera's half.
TEST_F(ViewExtractTorus, DenserOnTheCamerasHalf) {
  const Box3 box = bounds(*torus_);
  for (Vec3 dir : {Vec3{0.3f, 0.4f, 1}, Vec3{1, 0.6f, 0.2f}}) {
    McViewOptions o{.camera = camera_at(box, dir, 0.7f), .pixel_error = 4};
    o.camera.fov = 2;
    auto r = extract_mc_view(*model_, o);
    auto [near, far] = near_far(r.mesh, o.camera, box);
    EXPECT_GE(near, 2 * far) << near << " near, " << far << " far";
    EXPECT_TRUE(test::crack_report(r.mesh).ok());
  }
}

// Looking away, nothing is refined: at most 5 % of the full count.
TEST_F(ViewExtractTorus, LookingAwayStaysCoarse) {
  const Box3 box = bounds(*torus_);
  auto r =
      extract_mc_view(*model_, {.camera = camera_at(box, {0, 0, 1}, 3, true), .pixel_error = 0.5});
  EXPECT_LE(r.mesh.triangle_count(), model_->full_triangles() / 20);
  EXPECT_EQ(r.expanded, 0u);
  EXPECT_EQ(r.pixel_error, 0.0);
  // The same camera turned round refines.
  auto back =
      extract_mc_view(*model_, {.camera = camera_at(box, {0, 0, 1}, 3), .pixel_error = 0.5});
  EXPECT_GT(back.mesh.triangle_count(), 10 * r.mesh.triangle_count());
}

// The measured worst error (full-resolution samples against the result, at
// their own depth) is within the budget, and the budget is not free: a
// tenth of it is more triangles.
TEST_F(ViewExtractTorus, MeasuredErrorWithinThePixelBudget) {
  const TriangleMesh full = extract_mc_mesh(*model_).mesh;
  const Box3 box = bounds(*torus_);
  McViewExtractor ex(*model_);
  std::size_t finer = 0;
  for (double e : {8.0, 16.0, 32.0}) {
    McViewOptions o{.camera = camera_at(box, {0.3f, 0.4f, 1}, 1.5f), .pixel_error = e};
    auto r = ex.extract(o);
    const double measured = measured_pixel_error(full, r.mesh, o);
    EXPECT_LE(measured, e) << "budget " << e;
    EXPECT_LE(measured, r.pixel_error) << "the node bounds bound the measured error";
    EXPECT_GT(measured, 0.1 * e) << "the budget is used";
    const auto quarter = ex.extract({.camera = o.camera, .pixel_error = e / 4});
    EXPECT_GE(quarter.mesh.triangle_count(), r.mesh.triangle_count());
    finer += quarter.mesh.triangle_count() > r.mesh.triangle_count();
  }
  EXPECT_GE(finer, 2u);
}

// Degenerate cameras and budgets: DataError saying what is wrong.
TEST_F(ViewExtractTorus, BadCamerasAreErrors) {
  const McCamera ok;
  auto expect_error = [&](McViewOptions o, const char* what) {
    try {
      extract_mc_view(*model_, o);
      ADD_FAILURE() << "no error for " << what;
    } catch (const DataError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  McViewOptions o{.camera = ok};
  o.camera.look_at = o.camera.position;
  expect_error(o, "look-at equals");
  o = {.camera = ok};
  o.camera.up = {0, 0, 1};
  expect_error(o, "parallel");
  o = {.camera = ok};
  o.camera.fov = 3.2;
  expect_error(o, "field of view");
  o = {.camera = ok, .pixel_error = 0};
  expect_error(o, "pixel error");
}

// The Stanford bunny, closed: crack-free three box sizes away from several
// sides, denser near the camera, and the measured error within the budget.
TEST(ViewExtract, BunnyCrackFreeAndWithinTheBudget) {
  if (!std::filesystem::exists(kBunny)) GTEST_SKIP() << kBunny << " missing";
  const TriangleMesh bunny = read_mesh(kBunny);
  const McLodModel model = model_of(bunny, 64);
  const TriangleMesh full = extract_mc_mesh(model).mesh;
  const Box3 box = bounds(bunny);
  McViewExtractor ex(model);
  for (Vec3 dir : {Vec3{0, 0, 1}, Vec3{-1, 0.3f, 0.2f}, Vec3{0.4f, -0.2f, -1}}) {
    for (double e : {4.0, 16.0}) {
      McViewOptions o{.camera = camera_at(box, dir, 3), .pixel_error = e};
      auto r = ex.extract(o);
      auto report = test::crack_report(r.mesh);
      EXPECT_TRUE(report.ok()) << report.describe();
      EXPECT_LT(r.mesh.triangle_count(), model.full_triangles());
      EXPECT_LE(measured_pixel_error(full, r.mesh, o), e);
    }
  }
}

// The bunny with its holes open (the default build): nodes wholly over a hole
// cannot be placed and stay coarse; the cut is still within the budget,
// manifold, and no more open than the full-resolution mesh.
TEST(ViewExtract, OpenBunnyWithinTheBudget) {
  if (!std::filesystem::exists(kBunny)) GTEST_SKIP() << kBunny << " missing";
  const TriangleMesh bunny = read_mesh(kBunny);
  const McLodModel model =
      compile_mc_lod(build_mc_octree(bunny, {.resolution = 64, .holes = McHoles::kOpen}).tree);
  const TriangleMesh full = extract_mc_mesh(model).mesh;
  const auto full_report = test::crack_report(full);
  ASSERT_GT(full_report.topology.boundary_edges, 0u);
  McViewOptions o{.camera = camera_at(bounds(bunny), {0, -1, 0.3f}, 3), .pixel_error = 8};
  auto r = extract_mc_view(model, o);
  EXPECT_LT(r.mesh.triangle_count(), model.full_triangles());
  EXPECT_LE(measured_pixel_error(full, r.mesh, o), 8.0);
  const auto report = test::crack_report(r.mesh);
  EXPECT_EQ(report.topology.non_manifold_edges, 0u);
  EXPECT_LE(report.topology.boundary_edges, full_report.topology.boundary_edges);
}

}  // namespace
}  // namespace lodforge
