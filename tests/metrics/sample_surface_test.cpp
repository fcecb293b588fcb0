#include "lodforge/metrics/sample_surface.h"

#include <gtest/gtest.h>

#include "lodforge/metrics/closest_point_on_triangle.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

// Two triangles in z = 0 with areas 1 and 3.
TriangleMesh two_areas() {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {10, 0, 0}, {12, 0, 0}, {10, 3, 0}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  return m;
}

float distance_to_own_triangle(const TriangleMesh& m, const SurfaceSamples& s, std::size_t i) {
  const auto& t = m.triangles[s.triangles[i]];
  return std::sqrt(closest_point_on_triangle(s.positions[i], m.positions[t[0]], m.positions[t[1]],
                                             m.positions[t[2]])
                       .distance_squared);
}

TEST(SampleSurface, AreaWeightedAndOnTheirTriangles) {
  TriangleMesh m = two_areas();
  auto s = sample_surface(m, {.count = 1000, .vertices = false});
  ASSERT_EQ(s.size(), 1000u);
  EXPECT_DOUBLE_EQ(s.area, 4.0);
  std::size_t on_large = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    on_large += s.triangles[i] == 1;
    EXPECT_LT(distance_to_own_triangle(m, s, i), 1e-6f);
    EXPECT_EQ(s.normals[i], (Vec3{0, 0, 1}));
  }
  // Stratified: each triangle gets its share up to one sample.
  EXPECT_NEAR(double(on_large), 750.0, 1.0);
}

TEST(SampleSurface, DeterministicForASeed) {
  TriangleMesh m = test::make_icosphere(2);
  auto s1 = sample_surface(m, {.count = 5000, .seed = 7});
  auto s2 = sample_surface(m, {.count = 5000, .seed = 7});
  auto s3 = sample_surface(m, {.count = 5000, .seed = 8});
  EXPECT_EQ(s1.positions, s2.positions);
  EXPECT_EQ(s1.triangles, s2.triangles);
  EXPECT_NE(s1.positions, s3.positions);
}

TEST(SampleSurface, VerticesFirstThenEdgesThenArea) {
  TriangleMesh m = test::make_cube();
  m.positions.push_back({5, 5, 5});  // unused: not on the surface, not sampled
  auto s = sample_surface(m, {.count = 100, .edge_count = 50});
  EXPECT_EQ(s.vertex_samples, 8u);
  EXPECT_EQ(s.edge_samples, 50u);
  ASSERT_EQ(s.size(), 158u);
  for (std::size_t v = 0; v < 8; ++v) EXPECT_EQ(s.positions[v], m.positions[v]);
  for (std::size_t i = 8; i < 58; ++i) {
    // On one of the edges of its triangle.
    const auto& t = m.triangles[s.triangles[i]];
    float nearest = 1;
    for (int k = 0; k < 3; ++k) {
      const Vec3 &x = m.positions[t[k]], &y = m.positions[t[(k + 1) % 3]];
      nearest =
          std::min(nearest, closest_point_on_triangle(s.positions[i], x, y, y).distance_squared);
    }
    EXPECT_LT(nearest, 1e-12f) << i;
  }
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_LT(distance_to_own_triangle(m, s, i), 1e-6f);
}

TEST(SampleSurface, InterpolatesVertexNormalsWhenPresent) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}};
  m.normals = {{0, 0, 1}, {1, 0, 0}, {1, 0, 0}};
  auto s = sample_surface(m, {.count = 200});
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_NEAR(length(s.normals[i]), 1, 1e-5f);
    // Weight of vertex 0 is 1 - x - y; the normal leans to +x as it shrinks.
    float w0 = 1 - s.positions[i].x - s.positions[i].y;
    Vec3 expected = normalized(Vec3{1 - w0, 0, w0});
    EXPECT_NEAR(dot(s.normals[i], expected), 1, 1e-4f) << i;
  }
  auto flat = sample_surface(m, {.count = 10, .vertex_normals = false});
  for (const auto& n : flat.normals) EXPECT_EQ(n, (Vec3{0, 0, 1}));
}

TEST(SampleSurface, DegenerateTrianglesGetNoAreaSamples) {
  TriangleMesh m = two_areas();
  m.positions.push_back({20, 0, 0});
  m.triangles.push_back({3, 4, 3});  // collapsed to an edge
  m.triangles.push_back({6, 6, 6});  // collapsed to a point, last
  auto s = sample_surface(m, {.count = 500, .vertices = false});
  for (auto t : s.triangles) EXPECT_LT(t, 2u);
  auto pointlike = sample_surface(m, {.count = 500});
  EXPECT_EQ(pointlike.vertex_samples, 7u);
  // A mesh without area yields only its vertices.
  TriangleMesh flat;
  flat.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.triangles = {{0, 1, 2}};
  auto f = sample_surface(flat, {.count = 100});
  EXPECT_EQ(f.size(), 3u);
  EXPECT_EQ(f.area, 0.0);
}

}  // namespace
}  // namespace lodforge
