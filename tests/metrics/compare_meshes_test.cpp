#include "lodforge/metrics/compare_meshes.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <tbb/parallel_for.h>

#include <cfloat>
#include <cmath>
#include <filesystem>
#include <limits>

#include "core/progress_recorder.h"
#include "lodforge/core/error.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/metrics/closest_point_on_triangle.h"
#include "lodforge/metrics/sample_surface.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

using test::make_cube;
using test::make_icosphere;
using test::make_square;

TEST(CompareMeshes, IdenticalMeshesAreExactlyZero) {
  for (const TriangleMesh& m : {make_cube(), make_icosphere(3)}) {
    CompareResult r = compare_meshes(m, m, {.samples = 20'000, .edge_samples = 1000});
    for (const Deviation* d : {&r.a_to_b, &r.b_to_a}) {
      EXPECT_EQ(d->max, 0);
      EXPECT_EQ(d->mean, 0);
      EXPECT_EQ(d->rms, 0);
      EXPECT_EQ(d->variance, 0);
      EXPECT_EQ(d->normal.max, 0);
      EXPECT_EQ(d->normal.mean, 0);
      EXPECT_EQ(d->samples, 20'000 + 1000 + m.vertex_count());
    }
    EXPECT_EQ(r.hausdorff, 0);
    for (float v : r.vertex_deviation) EXPECT_EQ(v, 0);
  }
}

// A sample count whose samples cannot fit the memory budget is refused
// before anything is allocated, with the estimate.
TEST(CompareMeshes, SamplesBeyondTheMemoryBudgetAreRefused) {
  const TriangleMesh m = make_cube();
  try {
    compare_meshes(m, m, {.samples = std::numeric_limits<std::size_t>::max()});
    ADD_FAILURE() << "no error";
  } catch (const DataError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("comparing with 18446744073709551615 area samples "
                                               "per direction needs about 2.2e+12 GiB"));
  }
  // 1000 samples within a budget of 1 MiB pass; 10 000 (1.3 MB) do not.
  EXPECT_NO_THROW(compare_meshes(m, m, {.samples = 1000, .max_memory = 1 << 20}));
  EXPECT_THROW(compare_meshes(m, m, {.samples = 10'000, .max_memory = 1 << 20}), DataError);
}

TEST(CompareMeshes, IdenticalMeshesWithVertexNormals) {
  TriangleMesh m = make_icosphere(3);
  m.normals = m.positions;  // unit sphere: the position is the normal
  CompareResult r = compare_meshes(m, m, {.samples = 20'000});
  EXPECT_TRUE(r.vertex_normals);
  EXPECT_EQ(r.hausdorff, 0);
  EXPECT_LT(r.a_to_b.normal.max, 1e-3);  // barycentrics are recomputed, up to rounding
}

// Colour (p + 1) / 2 is linear in position, so interpolation inside a
// triangle gives it exactly: the colour distance between a sample and its
// closest point is then half their distance.
TriangleMesh colored_by_position(TriangleMesh m) {
  m.colors.clear();
  for (const Vec3& p : m.positions) m.colors.push_back((p + Vec3{1, 1, 1}) * 0.5f);
  return m;
}

TEST(CompareMeshes, ColourDeviationFollowsTheInterpolatedColours) {
  TriangleMesh fine = colored_by_position(make_icosphere(4));
  TriangleMesh coarse = colored_by_position(make_icosphere(2));
  CompareResult r = compare_meshes(fine, coarse, {.samples = 20'000});
  for (const Deviation* d : {&r.a_to_b, &r.b_to_a}) {
    EXPECT_GT(d->color.samples, 20'000u);
    EXPECT_GT(d->color.mean, 0);
    EXPECT_NEAR(d->color.mean, d->mean / 2, 1e-3 * d->mean);
    EXPECT_NEAR(d->color.max, d->max / 2, 1e-3 * d->max);
  }

  // Same surface, red shifted by 0.1 everywhere: every sample is 0.1 off.
  TriangleMesh shifted = fine;
  for (Vec3& c : shifted.colors) c.x += 0.1f;
  CompareResult same = compare_meshes(fine, shifted, {.samples = 5'000});
  EXPECT_EQ(same.hausdorff, 0);
  EXPECT_NEAR(same.a_to_b.color.mean, 0.1, 1e-4);
  EXPECT_NEAR(same.b_to_a.color.max, 0.1, 1e-4);

  // Colours on one side only: nothing to compare.
  CompareResult one = compare_meshes(fine, make_icosphere(2), {.samples = 5'000});
  EXPECT_EQ(one.a_to_b.color.samples, 0u);
  EXPECT_EQ(one.b_to_a.color.samples, 0u);
}

TEST(CompareMeshes, EstimatedNormalsAreSmooth) {
  // A fine sphere against a coarser one: face normals differ by about the
  // coarse facets' angular size; estimated vertex normals interpolate towards
  // the true radial normal on both, so the deviation shrinks.
  TriangleMesh fine = make_icosphere(4), coarse = make_icosphere(2);
  CompareResult faceted = compare_meshes(fine, coarse, {.samples = 20'000});
  CompareResult smooth =
      compare_meshes(fine, coarse, {.samples = 20'000, .estimate_normals = true});
  EXPECT_FALSE(faceted.vertex_normals);
  EXPECT_TRUE(smooth.vertex_normals);
  EXPECT_EQ(faceted.hausdorff, smooth.hausdorff);  // geometry is unchanged
  EXPECT_LT(smooth.a_to_b.normal.mean, 0.5 * faceted.a_to_b.normal.mean);
  EXPECT_LT(smooth.a_to_b.normal.max, 0.1);
}

TEST(CompareMeshes, CubeOffsetAlongAnAxisHasHausdorffD) {
  const float d = 0.25f;
  CompareResult r = compare_meshes(make_cube(), make_cube(1, {d, 0, 0}), {.samples = 50'000});
  EXPECT_NEAR(r.a_to_b.max, d, 1e-6);
  EXPECT_NEAR(r.b_to_a.max, d, 1e-6);
  EXPECT_NEAR(r.hausdorff, d, 1e-6);
  EXPECT_NEAR(r.diagonal, std::sqrt(3.0), 1e-6);
  EXPECT_NEAR(r.hausdorff_pct, 100 * d / std::sqrt(3.0), 1e-4);
  // Analytic mean A->B (total area 6): the face x = 0 (area 1) is d away;
  // on the four side faces the strip x in [0, d) is d - x away (mean d/2 over
  // area d each); the face x = 1 lies inside B, min(t, d) away from B's
  // surface, t its distance to the square's border, P(t > s) = (1 - 2s)^2,
  // so its mean is the integral of (1 - 2s)^2 over [0, d]; the rest lies
  // on B. B->A is the mirror image.
  double inner = (1 - std::pow(1 - 2 * d, 3)) / 6;
  double mean = (1 * d + 4 * d * d / 2 + inner) / 6;
  EXPECT_NEAR(r.a_to_b.mean, mean, 0.02 * mean);
  EXPECT_NEAR(r.b_to_a.mean, mean, 0.02 * mean);
  // Per vertex: the four corners at x = 0 are d away, those at x = 1 lie on B.
  ASSERT_EQ(r.vertex_deviation.size(), 8u);
  for (std::size_t v = 0; v < 8; ++v) {
    EXPECT_NEAR(r.vertex_deviation[v], (v & 1) ? 0 : d, 1e-6) << v;
  }
  // Normals: the inner face x = 1 is closest to B's side faces near its
  // border, at right angles; the face x = 0 and the strips face B's parallel
  // faces (the tie rule picks the parallel face along B's edges).
  EXPECT_NEAR(r.a_to_b.normal.max, kPi / 2, 1e-6);
  EXPECT_GT(r.a_to_b.normal.mean, 0.1);
}

TEST(CompareMeshes, SphereAgainstItsIcosahedron) {
  // S: level-5 icosphere of radius 1 (20 480 triangles, within 3e-4 of the
  // unit sphere); I: the icosahedron inscribed in the same sphere.
  // Analytic: the sphere's farthest points from I are above the face
  // centres, at R - r with inradius r = R sqrt((5 + 2 sqrt 5) / 15); I's
  // farthest points from the sphere are the same face centres. The mean
  // distance from I to the sphere is R - E|x| over I's surface (by symmetry,
  // over one face), integrated here on a fine subdivision.
  const double R = 1, r = R * std::sqrt((5 + 2 * std::sqrt(5.0)) / 15);
  const double sag = 3e-4;  // how far S's flat triangles dip below the sphere
  TriangleMesh s = make_icosphere(5), ico = make_icosphere(0);
  CompareResult res = compare_meshes(s, ico, {.samples = 200'000});
  EXPECT_NEAR(res.a_to_b.max, R - r, sag);
  EXPECT_NEAR(res.b_to_a.max, R - r, sag);
  EXPECT_LE(res.b_to_a.max, R - r + 1e-6);
  EXPECT_NEAR(res.hausdorff, R - r, sag);

  const auto& t = ico.triangles[0];
  Vec3 a = ico.positions[t[0]], b = ico.positions[t[1]], c = ico.positions[t[2]];
  const int n = 400;
  double sum = 0;
  int cells = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; i + j < n; ++j) {
      // Centroids of the n^2 equal sub-triangles (upward and downward).
      for (int up = 0; up < (i + j + 1 < n ? 2 : 1); ++up) {
        double u = (i + (up ? 2.0 / 3 : 1.0 / 3)) / n, v = (j + (up ? 2.0 / 3 : 1.0 / 3)) / n;
        double x = a.x * (1 - u - v) + b.x * u + c.x * v, y = a.y * (1 - u - v) + b.y * u + c.y * v,
               z = a.z * (1 - u - v) + b.z * u + c.z * v;
        sum += std::sqrt(x * x + y * y + z * z);
        ++cells;
      }
    }
  }
  ASSERT_EQ(cells, n * n);
  double mean_gap = R - sum / cells;
  EXPECT_NEAR(res.b_to_a.mean, mean_gap, sag + 2e-4);
}

TEST(CompareMeshes, OneSidedDistancesDifferForAPatchOnAPlane) {
  // Figure 5.3 of seed 000: a small patch lying on a large plane. Every
  // point of the patch is on the plane, but the plane's far corner
  // (-10,-10) is 10 sqrt 2 from the patch's corner (0,0).
  TriangleMesh patch = make_square(0, 0, 1, 1), plane = make_square(-10, -10, 10, 10);
  CompareResult r = compare_meshes(patch, plane, {.samples = 20'000});
  EXPECT_EQ(r.a_to_b.max, 0);
  EXPECT_NEAR(r.b_to_a.max, 10 * std::sqrt(2.0), 1e-5);
  EXPECT_GT(r.b_to_a.mean, 5);
  EXPECT_EQ(r.hausdorff, r.b_to_a.max);
  EXPECT_NEAR(r.diagonal, std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(r.hausdorff_pct, 1000, 1e-3);
  EXPECT_EQ(r.a_to_b.normal.max, 0);
  EXPECT_EQ(r.b_to_a.normal.max, 0);
}

TEST(CompareMeshes, EmptyMeshThrowsNamingIt) {
  TriangleMesh empty;
  EXPECT_THAT([&] { compare_meshes(make_cube(), empty, {.b_name = "out.ply"}); },
              testing::ThrowsMessage<DataError>(
                  "compare: out.ply has no triangles, so there is no surface to measure"));
  EXPECT_THAT([&] { compare_meshes(empty, make_cube()); },
              testing::ThrowsMessage<DataError>(
                  "compare: A has no triangles, so there is no surface to measure"));
  TriangleMesh points = make_cube();
  points.triangles.clear();  // vertices but no surface
  EXPECT_THROW(compare_meshes(make_cube(), points), DataError);
}

TEST(CompareMeshes, BadDataThrows) {
  TriangleMesh bad = make_cube();
  bad.triangles.push_back({0, 1, 99});
  EXPECT_THAT(
      [&] { compare_meshes(make_cube(), bad); },
      testing::ThrowsMessage<DataError>("compare: B: triangle 12 uses vertex 99 of only 8"));
  TriangleMesh nan = make_cube();
  nan.positions[3].y = std::nanf("");
  EXPECT_THAT([&] { compare_meshes(nan, make_cube()); },
              testing::ThrowsMessage<DataError>(testing::HasSubstr("non-finite")));
}

TEST(CompareMeshes, AwkwardTopologyIsHandled) {
  // Duplicate vertices (each triangle its own three), an open border (a
  // missing face), a degenerate triangle and a second component.
  TriangleMesh cube = make_cube(), soup;
  for (std::size_t f = 0; f + 1 < cube.triangles.size(); ++f) {
    auto base = std::uint32_t(soup.positions.size());
    for (auto v : cube.triangles[f]) soup.positions.push_back(cube.positions[v]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  soup.triangles.push_back({0, 0, 1});
  TriangleMesh far = make_cube(1, {5, 0, 0});
  auto base = std::uint32_t(soup.positions.size());
  soup.positions.insert(soup.positions.end(), far.positions.begin(), far.positions.end());
  for (auto t : far.triangles) soup.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});

  CompareResult same = compare_meshes(soup, soup, {.samples = 10'000});
  EXPECT_EQ(same.hausdorff, 0);
  // Against the lone cube: every point of the second component's face x = 6
  // is 5 from the cube. Back, the hole left by the missing triangle
  // (1,1,0)-(1,1,1)-(1,0,1) is farthest from the soup at its incentre, the
  // inradius (2 - sqrt 2) / 2 from all three edges.
  CompareResult r = compare_meshes(soup, make_cube(), {.samples = 10'000});
  EXPECT_NEAR(r.a_to_b.max, 5, 1e-5);
  const double inradius = (2 - std::sqrt(2.0)) / 2;
  EXPECT_LE(r.b_to_a.max, inradius + 1e-6);
  EXPECT_NEAR(r.b_to_a.max, inradius, 0.03);
}

TEST(CompareMeshes, DeterministicWhateverTheThreadCount) {
  TriangleMesh s = make_icosphere(4), ico = make_icosphere(1);
  CompareResult one = compare_meshes(s, ico, {.samples = 30'000, .seed = 5, .threads = 1});
  CompareResult two = compare_meshes(s, ico, {.samples = 30'000, .seed = 5, .threads = 2});
  EXPECT_EQ(one.a_to_b.mean, two.a_to_b.mean);
  EXPECT_EQ(one.b_to_a.variance, two.b_to_a.variance);
  EXPECT_EQ(one.a_to_b.normal.mean, two.a_to_b.normal.mean);
  EXPECT_EQ(one.vertex_deviation, two.vertex_deviation);
}

TEST(CompareMeshes, ReportsTheSamplesOfEachDirection) {
  test::ProgressRecorder progress;
  compare_meshes(make_cube(), make_icosphere(3),
                 {.samples = 100'000, .progress = progress.callback()});
  EXPECT_EQ(progress.stages(), (std::vector<std::string>{"A to B", "B to A", "vertices"}));
  for (const auto& stage : progress.stages()) EXPECT_TRUE(progress.completed(stage)) << stage;
  // Every 16 384 samples, not every sample.
  EXPECT_LE(progress.calls("A to B"), 2 + 100'000 / 16'384 + 1);
}

TEST(CompareMeshes, DefaultSampleCount) {
  TriangleMesh s = make_icosphere(4);  // 5120 triangles -> 10 x 5120 < 100 000
  CompareResult r = compare_meshes(s, s, {.per_vertex = false});
  EXPECT_EQ(r.samples, 100'000u);
  EXPECT_TRUE(r.vertex_deviation.empty());
}

// Brute-force reference for one direction: every sample against every
// triangle, the same noise snap as compare_meshes. Returns {max, mean over
// the area samples}.
std::pair<double, double> brute_force(const SurfaceSamples& s, const TriangleMesh& other,
                                      float noise) {
  std::vector<float> d(s.size());
  tbb::parallel_for(std::size_t(0), s.size(), [&](std::size_t i) {
    float best = std::numeric_limits<float>::infinity();
    for (const auto& t : other.triangles) {
      best = std::min(best, closest_point_on_triangle(s.positions[i], other.positions[t[0]],
                                                      other.positions[t[1]], other.positions[t[2]])
                                .distance_squared);
    }
    float e = std::sqrt(best);
    d[i] = e <= noise ? 0.f : e;
  });
  double sum = 0;
  std::size_t first = s.vertex_samples + s.edge_samples;
  for (std::size_t i = first; i < d.size(); ++i) sum += d[i];
  return {*std::max_element(d.begin(), d.end()), sum / double(d.size() - first)};
}

TEST(CompareMeshes, StanfordBunnyAgreesWithBruteForce) {
  const std::string dir = LODFORGE_SHARED_DATA "/meshes/";
  if (!std::filesystem::exists(dir + "bun_zipper.ply") ||
      !std::filesystem::exists(dir + "bun_zipper_res3.ply")) {
    GTEST_SKIP() << "Stanford bunny not in " << dir;
  }
  TriangleMesh full = read_mesh(dir + "bun_zipper.ply");
  TriangleMesh low = read_mesh(dir + "bun_zipper_res3.ply");
  ASSERT_EQ(full.triangle_count(), 69'451u);
  ASSERT_EQ(low.triangle_count(), 3'851u);

  // Area samples only: brute force costs #samples x #triangles, and the
  // bunny's 35 947 vertices would make that minutes.
  const CompareOptions options{
      .samples = 1'500, .seed = 11, .vertices = false, .per_vertex = false};
  CompareResult r = compare_meshes(full, low, options);

  // The same samples compare_meshes draws (its header: seed for A, seed + 1
  // for B, face normals as the bunny has none).
  ASSERT_FALSE(r.vertex_normals);
  SurfaceSamples on_full = sample_surface(full, {.count = 1'500, .seed = 11, .vertices = false});
  SurfaceSamples on_low = sample_surface(low, {.count = 1'500, .seed = 12, .vertices = false});
  ASSERT_EQ(on_full.size(), r.a_to_b.samples);
  ASSERT_EQ(on_low.size(), r.b_to_a.samples);
  Box3 box = full.bounds();
  box.add(low.bounds());
  float extent = 0;
  for (int k = 0; k < 3; ++k) extent = std::max({extent, std::abs(box.lo[k]), std::abs(box.hi[k])});
  const float noise = 16 * FLT_EPSILON * extent;

  auto [max_ab, mean_ab] = brute_force(on_full, low, noise);
  auto [max_ba, mean_ba] = brute_force(on_low, full, noise);
  EXPECT_NEAR(r.a_to_b.max, max_ab, 0.02 * max_ab);
  EXPECT_NEAR(r.a_to_b.mean, mean_ab, 0.02 * mean_ab);
  EXPECT_NEAR(r.b_to_a.max, max_ba, 0.02 * max_ba);
  EXPECT_NEAR(r.b_to_a.mean, mean_ba, 0.02 * mean_ba);
  EXPECT_NEAR(r.hausdorff, std::max(max_ab, max_ba), 0.02 * std::max(max_ab, max_ba));
  // Plausible magnitudes: res3 keeps the bunny's shape to a fraction of a
  // percent of its 0.25 m diagonal on average.
  EXPECT_NEAR(r.diagonal, 0.2502, 0.001);
  EXPECT_GT(r.a_to_b.mean_pct, 0.01);
  EXPECT_LT(r.a_to_b.mean_pct, 1.0);
}

}  // namespace
}  // namespace lodforge
