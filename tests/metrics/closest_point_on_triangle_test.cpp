#include "lodforge/metrics/closest_point_on_triangle.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lodforge {
namespace {

// Right triangle in the z = 0 plane: a at the origin, b on x, c on y.
const Vec3 kA{0, 0, 0}, kB{2, 0, 0}, kC{0, 2, 0};

void expect_point(const TrianglePoint& r, Vec3 q, std::array<float, 3> w, float d2) {
  EXPECT_NEAR(r.point.x, q.x, 1e-6f);
  EXPECT_NEAR(r.point.y, q.y, 1e-6f);
  EXPECT_NEAR(r.point.z, q.z, 1e-6f);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.barycentric[k], w[k], 1e-6f) << k;
  EXPECT_NEAR(r.distance_squared, d2, 1e-5f);
}

TEST(ClosestPointOnTriangle, FaceRegionProjectsOntoThePlane) {
  auto r = closest_point_on_triangle({0.5f, 0.5f, 3}, kA, kB, kC);
  expect_point(r, {0.5f, 0.5f, 0}, {0.5f, 0.25f, 0.25f}, 9);
}

TEST(ClosestPointOnTriangle, PointOnTheTriangleIsItsOwnClosestPoint) {
  auto r = closest_point_on_triangle({0.5f, 1, 0}, kA, kB, kC);
  expect_point(r, {0.5f, 1, 0}, {0.25f, 0.25f, 0.5f}, 0);
}

TEST(ClosestPointOnTriangle, VertexRegions) {
  expect_point(closest_point_on_triangle({-1, -1, 1}, kA, kB, kC), kA, {1, 0, 0}, 3);
  expect_point(closest_point_on_triangle({3, -1, 0}, kA, kB, kC), kB, {0, 1, 0}, 2);
  expect_point(closest_point_on_triangle({-1, 4, 2}, kA, kB, kC), kC, {0, 0, 1}, 1 + 4 + 4);
}

TEST(ClosestPointOnTriangle, EdgeRegions) {
  // Below edge ab.
  expect_point(closest_point_on_triangle({0.5f, -2, 0}, kA, kB, kC), {0.5f, 0, 0},
               {0.75f, 0.25f, 0}, 4);
  // Left of edge ac, raised.
  expect_point(closest_point_on_triangle({-1, 1.5f, 1}, kA, kB, kC), {0, 1.5f, 0},
               {0.25f, 0, 0.75f}, 2);
  // Beyond the hypotenuse bc: its closest point is the midpoint (1,1).
  expect_point(closest_point_on_triangle({2, 2, 0}, kA, kB, kC), {1, 1, 0}, {0, 0.5f, 0.5f}, 2);
}

TEST(ClosestPointOnTriangle, DegenerateCollinearTriangleActsAsItsLongestSegment) {
  // c lies between a and b: the triangle is the segment a-b.
  Vec3 a{0, 0, 0}, b{4, 0, 0}, c{1, 0, 0};
  auto r = closest_point_on_triangle({2, 3, 0}, a, b, c);
  expect_point(r, {2, 0, 0}, {0.5f, 0.5f, 0}, 9);
  // Beyond b.
  r = closest_point_on_triangle({6, 0, 0}, a, b, c);
  expect_point(r, b, {0, 1, 0}, 4);
  // The longest edge may be b-c or c-a; the weights follow the corners.
  r = closest_point_on_triangle({2, 1, 0}, c, a, b);
  expect_point(r, {2, 0, 0}, {0, 0.5f, 0.5f}, 1);
}

TEST(ClosestPointOnTriangle, DegeneratePointTriangle) {
  Vec3 a{1, 1, 1};
  auto r = closest_point_on_triangle({1, 1, 3}, a, a, a);
  EXPECT_EQ(r.point, a);
  EXPECT_FLOAT_EQ(r.distance_squared, 4);
  EXPECT_FLOAT_EQ(r.barycentric[0] + r.barycentric[1] + r.barycentric[2], 1);
}

TEST(ClosestPointOnTriangle, NearlyDegenerateSliverStaysFinite) {
  Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0.5f, 1e-9f, 0};
  auto r = closest_point_on_triangle({0.5f, 1, 0}, a, b, c);
  EXPECT_TRUE(std::isfinite(r.distance_squared));
  EXPECT_NEAR(r.distance_squared, 1, 1e-5f);
}

TEST(ClosestPointOnTriangle, MatchesDenseSearchOnRandomCases) {
  // Against a brute-force minimum over a fine barycentric grid.
  std::uint32_t state = 12345;
  auto rnd = [&] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1 << 24) * 4 - 2;
  };
  for (int iter = 0; iter < 200; ++iter) {
    Vec3 a{rnd(), rnd(), rnd()}, b{rnd(), rnd(), rnd()}, c{rnd(), rnd(), rnd()};
    Vec3 p{rnd(), rnd(), rnd()};
    auto r = closest_point_on_triangle(p, a, b, c);
    float best = std::numeric_limits<float>::max();
    const int n = 200;
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        float v = float(i) / n, w = float(j) / n;
        best = std::min(best, length_squared(p - (a * (1 - v - w) + b * v + c * w)));
      }
    }
    EXPECT_LE(r.distance_squared, best + 1e-5f);
    EXPECT_GE(std::sqrt(r.distance_squared), std::sqrt(best) - 0.05f);
    Vec3 q = a * r.barycentric[0] + b * r.barycentric[1] + c * r.barycentric[2];
    EXPECT_NEAR(length(q - r.point), 0, 1e-5f);
  }
}

}  // namespace
}  // namespace lodforge
