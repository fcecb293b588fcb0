#include "lodforge/mesh/triangulate_polygon.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace lodforge {
namespace {

/// Sum of the triangles' areas projected on n (signed: wrong winding subtracts).
double signed_area(std::span<const Vec3> pts, const TriangulateResult& r, const Vec3& n) {
  double a = 0;
  for (const Triangle& t : r.triangles)
    a += 0.5 * dot(cross(pts[t[1]] - pts[t[0]], pts[t[2]] - pts[t[0]]), n);
  return a;
}

/// Every corner used, indices in range, n-2 triangles.
void expect_valid(std::span<const Vec3> pts, const TriangulateResult& r) {
  ASSERT_EQ(r.triangles.size(), pts.size() - 2);
  for (const Triangle& t : r.triangles)
    for (std::uint32_t i : t) EXPECT_LT(i, pts.size());
}

double polygon_area(std::span<const Vec3> p) {  // planar, in z = 0
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& u = p[i];
    const Vec3& v = p[(i + 1) % p.size()];
    a += 0.5 * (u.x * v.y - v.x * u.y);
  }
  return a;
}

TEST(TriangulatePolygon, TriangleIsItself) {
  std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  auto r = triangulate_polygon(p);
  ASSERT_EQ(r.triangles.size(), 1u);
  EXPECT_EQ(r.triangles[0], (Triangle{0, 1, 2}));
  EXPECT_FALSE(r.has_warning());
  EXPECT_NEAR(r.normal.z, 1.0f, 1e-6);
}

TEST(TriangulatePolygon, FewerThanThreeCornersGiveNothing) {
  std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}};
  auto r = triangulate_polygon(p);
  EXPECT_TRUE(r.triangles.empty());
  EXPECT_TRUE(r.degenerate);
}

TEST(TriangulatePolygon, FlatConvexQuadIsKept) {
  std::vector<Vec3> p = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  auto r = triangulate_polygon(p);
  expect_valid(p, r);
  EXPECT_TRUE(r.keep_as_quad);
  EXPECT_FALSE(r.has_warning());
  EXPECT_NEAR(signed_area(p, r, {0, 0, 1}), 2.0, 1e-6);
}

TEST(TriangulatePolygon, NoQuadsAlwaysSplits) {
  std::vector<Vec3> p = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  auto r = triangulate_polygon(p, {.keep_quads = false});
  expect_valid(p, r);
  EXPECT_FALSE(r.keep_as_quad);
}

TEST(TriangulatePolygon, ConcaveQuadIsSplitThroughTheReflexCorner) {
  // A dart: corner 2 is reflex, so only the diagonal 0-2 is inside.
  std::vector<Vec3> p = {{0, 0, 0}, {2, -1, 0}, {0.5f, 0, 0}, {2, 1, 0}};
  auto r = triangulate_polygon(p);
  expect_valid(p, r);
  EXPECT_FALSE(r.keep_as_quad);
  EXPECT_FALSE(r.has_warning());
  for (const Triangle& t : r.triangles) {
    EXPECT_TRUE(std::find(t.begin(), t.end(), 2u) != t.end());
    EXPECT_TRUE(std::find(t.begin(), t.end(), 0u) != t.end());
  }
  EXPECT_NEAR(signed_area(p, r, {0, 0, 1}), polygon_area(p), 1e-6);
}

double bend(std::span<const Vec3> p, const Triangle& a, const Triangle& b) {
  Vec3 n1 = normalized(cross(p[a[1]] - p[a[0]], p[a[2]] - p[a[0]]));
  Vec3 n2 = normalized(cross(p[b[1]] - p[b[0]], p[b[2]] - p[b[0]]));
  return std::acos(std::clamp(static_cast<double>(dot(n1, n2)), -1.0, 1.0));
}

TEST(TriangulatePolygon, BentQuadIsSplitAlongTheFlatterDiagonal) {
  // Corner 3 lifted: 0.6 rad (34 degrees) of bend, well over the 10 degree default.
  std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.2f}, {0, 1, 0.9f}};
  auto r = triangulate_polygon(p);
  expect_valid(p, r);
  EXPECT_FALSE(r.keep_as_quad);
  double chosen = bend(p, r.triangles[0], r.triangles[1]);
  double along_02 = bend(p, {0, 1, 2}, {0, 2, 3});
  double along_13 = bend(p, {1, 2, 3}, {1, 3, 0});
  EXPECT_NEAR(chosen, std::min(along_02, along_13), 1e-6);
  EXPECT_GT(std::max(along_02, along_13), 0.174533);
}

TEST(TriangulatePolygon, SlightlyBentQuadIsKept) {
  std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.05f}};  // ~3 degrees
  auto r = triangulate_polygon(p);
  EXPECT_TRUE(r.keep_as_quad);
  auto strict = triangulate_polygon(p, {.quad_split_angle = 0.01f});
  EXPECT_FALSE(strict.keep_as_quad);
}

TEST(TriangulatePolygon, ConcaveLShape) {
  std::vector<Vec3> p = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  auto r = triangulate_polygon(p);
  expect_valid(p, r);
  EXPECT_FALSE(r.has_warning());
  EXPECT_NEAR(signed_area(p, r, {0, 0, 1}), 3.0, 1e-6);
  for (const Triangle& t : r.triangles)  // every triangle wound like the polygon
    EXPECT_GT(dot(cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]), Vec3{0, 0, 1}), 0);
}

TEST(TriangulatePolygon, ClockwisePolygonKeepsItsWinding) {
  std::vector<Vec3> p = {{0, 2, 0}, {1, 2, 0}, {1, 1, 0}, {2, 1, 0}, {2, 0, 0}, {0, 0, 0}};
  auto r = triangulate_polygon(p);
  expect_valid(p, r);
  EXPECT_NEAR(r.normal.z, -1.0f, 1e-6);
  for (const Triangle& t : r.triangles)
    EXPECT_LT(dot(cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]), Vec3{0, 0, 1}), 0);
}

TEST(TriangulatePolygon, StarShapedPolygonsAreExact) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> radius(0.2f, 1.0f);
  for (int trial = 0; trial < 200; ++trial) {
    int n = 5 + trial % 40;
    std::vector<Vec3> p;
    for (int i = 0; i < n; ++i) {
      double a = 2 * kPi * i / n;
      float r = radius(rng);
      p.push_back({static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), 0});
    }
    auto r = triangulate_polygon(p);
    expect_valid(p, r);
    EXPECT_FALSE(r.not_simple) << "trial " << trial;
    EXPECT_NEAR(signed_area(p, r, {0, 0, 1}), polygon_area(p), 1e-5) << "trial " << trial;
  }
}

TEST(TriangulatePolygon, NonPlanarPolygon) {
  // A crown: a circle whose corners go up and down.
  std::vector<Vec3> p;
  for (int i = 0; i < 12; ++i) {
    double a = 2 * kPi * i / 12;
    p.push_back(
        {static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), (i % 2) ? 0.3f : -0.3f});
  }
  auto r = triangulate_polygon(p);
  expect_valid(p, r);
  EXPECT_FALSE(r.has_warning());
  EXPECT_NEAR(r.normal.z, 1.0f, 1e-5);
}

TEST(TriangulatePolygon, CollinearCornerOnAnEdge) {
  std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  auto r = triangulate_polygon(p);
  expect_valid(p, r);
  EXPECT_FALSE(r.has_warning());
  EXPECT_NEAR(signed_area(p, r, {0, 0, 1}), 4.0, 1e-6);
}

TEST(TriangulatePolygon, AllCollinearIsFlaggedButStillTriangulated) {
  std::vector<Vec3> p = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}, {4, 4, 4}};
  auto r = triangulate_polygon(p);
  expect_valid(p, r);
  EXPECT_TRUE(r.degenerate);
  EXPECT_EQ(r.normal, Vec3{});
}

TEST(TriangulatePolygon, CoincidentCornersAreFlagged) {
  std::vector<Vec3> p(6, Vec3{1, 2, 3});
  auto r = triangulate_polygon(p);
  expect_valid(p, r);
  EXPECT_TRUE(r.degenerate);
}

TEST(TriangulatePolygon, BowTieQuadIsFlagged) {
  std::vector<Vec3> p = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
  auto r = triangulate_polygon(p);
  expect_valid(p, r);
  EXPECT_TRUE(r.has_warning());
  EXPECT_FALSE(r.keep_as_quad);
}

TEST(TriangulatePolygon, PentagramIsFlaggedButComplete) {
  std::vector<Vec3> p;
  for (int i = 0; i < 5; ++i) {
    double a = 2 * kPi * (2 * i % 5) / 5;
    p.push_back({static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0});
  }
  auto r = triangulate_polygon(p);
  expect_valid(p, r);
  EXPECT_TRUE(r.has_warning());
}

TEST(TriangulatePolygon, NonFiniteInputDoesNotCrash) {
  float nan = std::nanf("");
  std::vector<Vec3> p = {{0, 0, 0}, {nan, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 2, 0}};
  auto r = triangulate_polygon(p);
  expect_valid(p, r);
  EXPECT_TRUE(r.degenerate);
}

TEST(TriangulatePolygon, IndexedOverloadReturnsCornerNumbers) {
  std::vector<Vec3> pos = {{9, 9, 9}, {0, 0, 0}, {2, 0, 0}, {2, 1, 0},
                           {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  std::vector<std::uint32_t> idx = {1, 2, 3, 4, 5, 6};
  auto r = triangulate_polygon(pos, idx);
  ASSERT_EQ(r.triangles.size(), 4u);
  for (const Triangle& t : r.triangles)
    for (std::uint32_t c : t) EXPECT_LT(c, 6u);
}

TEST(TriangulatePolygon, LargeCircleIsFast) {
  std::vector<Vec3> p;
  for (int i = 0; i < 2000; ++i) {
    double a = 2 * kPi * i / 2000;
    p.push_back({static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0});
  }
  auto r = triangulate_polygon(p);
  expect_valid(p, r);
  EXPECT_NEAR(signed_area(p, r, {0, 0, 1}), polygon_area(p), 1e-4);
}

// Polygons of 100 000 corners (one polygon of a huge OBJ face): a circle
// (convex), a star (every other corner reflex), random radii, and a comb of
// 5 000 long teeth (20 000 corners: its bottom edge of collinear corners is
// the quadratic case) all triangulate completely, with the polygon's area.
TEST(TriangulatePolygon, HugePolygonsAreComplete) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> radius(0.5f, 1.0f);
  for (int shape = 0; shape < 4; ++shape) {
    const int n = shape == 3 ? 20'000 : 100'000;
    std::vector<Vec3> p;
    for (int i = 0; i < n; ++i) {
      if (shape == 3) {  // tooth i / 4: up, across, down
        const int t = i % 4;
        p.push_back({float(i / 4) + (t >= 2 ? 0.5f : 0.f), (t == 1 || t == 2) ? 10.f : 0.f, 0});
        continue;
      }
      const float r = shape == 0 ? 1.f : shape == 1 ? (i % 2 ? 0.5f : 1.f) : radius(rng);
      const double a = 2 * kPi * i / n;
      p.push_back({float(r * std::cos(a)), float(r * std::sin(a)), 0});
    }
    if (shape == 3) p.insert(p.end(), {{float(n / 4), -5, 0}, {0, -5, 0}});
    auto r = triangulate_polygon(p);
    expect_valid(p, r);
    EXPECT_FALSE(r.not_simple) << "shape " << shape;
    const double area = polygon_area(p);
    EXPECT_NEAR(signed_area(p, r, {0, 0, 1}), area, 1e-4 * std::abs(area)) << "shape " << shape;
  }
}

}  // namespace
}  // namespace lodforge

namespace lodforge {
namespace {

TEST(TriangleIsDegenerate, AgreesWithTriangulatePolygon) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  int flagged = 0;
  for (int i = 0; i < 20000; ++i) {
    Vec3 a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
    if (i % 4 == 1) c = a + (b - a) * u(rng);                    // collinear
    if (i % 4 == 2) c = b;                                       // two corners at one place
    if (i % 4 == 3) c = a + (b - a) * 0.5f + Vec3{0, 0, 1e-9f};  // almost collinear
    const Vec3 corners[3] = {a, b, c};
    const bool expected = triangulate_polygon(corners).degenerate;
    EXPECT_EQ(triangle_is_degenerate(a, b, c), expected) << i;
    flagged += expected;
  }
  EXPECT_GE(flagged, 5000);  // the coincident corners at least
}

}  // namespace
}  // namespace lodforge
