#include "lodforge/metrics/triangle_bvh.h"

#include <gtest/gtest.h>

#include <random>

#include "lodforge/metrics/closest_point_on_triangle.h"
#include "lodforge/metrics/ray.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

float brute_force(const TriangleMesh& m, const Vec3& p) {
  float best = std::numeric_limits<float>::infinity();
  for (const auto& t : m.triangles) {
    best = std::min(
        best, closest_point_on_triangle(p, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]])
                  .distance_squared);
  }
  return best;
}

// A bumpy sphere plus a detached sheet, a sliver, a collapsed triangle and
// duplicated vertices: the shapes a BVH must not mishandle.
TriangleMesh awkward_mesh() {
  TriangleMesh m = test::make_icosphere(3);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> bump(0.9f, 1.1f);
  for (auto& p : m.positions) p *= bump(rng);
  auto base = std::uint32_t(m.positions.size());
  m.positions.insert(m.positions.end(),
                     {{3, 0, 0}, {4, 0, 0}, {3, 1, 0}, {3, 0, 0}, {5, 5, 5}, {6, 5, 5}, {7, 5, 5}});
  m.triangles.push_back({base, base + 1, base + 2});
  m.triangles.push_back({base + 3, base + 2, base + 1});  // duplicate vertex 3 == 0
  m.triangles.push_back({base + 4, base + 5, base + 6});  // collinear
  m.triangles.push_back({base + 4, base + 4, base + 4});  // a point
  return m;
}

TEST(TriangleBvh, EqualsBruteForceOnRandomQueries) {
  TriangleMesh m = awkward_mesh();
  for (int leaf : {1, 4, 8, -1, -4, -8}) {  // negative: the Morton build
    TriangleBvh bvh(
        m, {.leaf_size = std::abs(leaf), .build = leaf < 0 ? BvhBuild::kMorton : BvhBuild::kSah});
    std::mt19937 rng(std::abs(leaf));
    std::uniform_real_distribution<float> coord(-3, 8);
    for (int i = 0; i < 2000; ++i) {
      Vec3 p{coord(rng), coord(rng), coord(rng)};
      ClosestPoint c = bvh.closest_point(p);
      ASSERT_TRUE(c.found());
      float expected = brute_force(m, p);
      EXPECT_EQ(c.distance_squared, expected) << i;
      // A hint (here any triangle) and the normal tie rule never change the distance.
      auto hint = std::uint32_t(rng() % m.triangles.size());
      EXPECT_EQ(bvh.closest_point(p, hint).distance_squared, expected) << i;
      EXPECT_EQ(bvh.closest_point(p, Vec3{0, 0, 1}, hint).distance_squared, expected) << i;
      // The reported triangle and barycentrics reproduce the point.
      const auto& t = m.triangles[c.triangle];
      Vec3 q = m.positions[t[0]] * c.barycentric[0] + m.positions[t[1]] * c.barycentric[1] +
               m.positions[t[2]] * c.barycentric[2];
      EXPECT_LT(length(q - c.point), 1e-5f);
      EXPECT_NEAR(length_squared(p - c.point), c.distance_squared, 1e-4f);
    }
  }
}

// first_hit: the nearest crossing over all triangles (a triangle hit at that
// t: the sheet is there twice, its copy wound the other way), for random rays and for axis-parallel
// ones (zero direction components; the sheet at z = 0 has a box of zero thickness), with both
// builds; a max_distance short of the hit misses.
TEST(TriangleBvh, FirstHitEqualsBruteForce) {
  TriangleMesh m = awkward_mesh();
  auto brute = [&](const Vec3& o, const Vec3& d) {
    RayHit best;
    const Ray ray(o, normalized(d));
    for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
      const auto& f = m.triangles[t];
      double s = ray.hit(m.positions[f[0]], m.positions[f[1]], m.positions[f[2]]);
      if (s >= 0 && static_cast<float>(s) < best.distance) best = {static_cast<float>(s), t};
    }
    return best;
  };
  for (int leaf : {1, 4, -4}) {
    TriangleBvh bvh(
        m, {.leaf_size = std::abs(leaf), .build = leaf < 0 ? BvhBuild::kMorton : BvhBuild::kSah});
    std::mt19937 rng(10 + leaf);
    std::uniform_real_distribution<float> coord(-3, 8);
    std::uniform_real_distribution<float> aim(-1, 1);
    std::normal_distribution<float> g;
    int hits = 0;
    for (int i = 0; i < 4000; ++i) {
      const Vec3 o{coord(rng), coord(rng), coord(rng)};
      Vec3 d{g(rng), g(rng), g(rng)};
      if (i % 4 == 0) d = {0, 0, -1};
      if (i % 4 == 1) d = Vec3{0, coord(rng), coord(rng)} - o, d.x = 0;
      if (i % 4 == 2) d = Vec3{aim(rng), aim(rng), aim(rng)} - o;  // at the sphere
      const RayHit expect = brute(o, d), got = bvh.first_hit(o, d);
      ASSERT_EQ(got.hit(), expect.hit()) << i;
      if (!got.hit()) continue;
      ++hits;
      EXPECT_EQ(got.distance, expect.distance) << i;
      const auto& f = m.triangles[got.triangle];
      EXPECT_EQ(
          static_cast<float>(
              Ray(o, normalized(d)).hit(m.positions[f[0]], m.positions[f[1]], m.positions[f[2]])),
          got.distance)
          << i;
      if (got.distance > 0) EXPECT_FALSE(bvh.first_hit(o, d, 0.99f * got.distance).hit()) << i;
    }
    EXPECT_GT(hits, 800) << leaf;
  }
  // Straight down onto the sheet (3..4, 0..1 at z = 0).
  TriangleBvh bvh(m);
  RayHit h = bvh.first_hit({3.25f, 0.25f, 2}, {0, 0, -5});
  ASSERT_TRUE(h.hit());
  EXPECT_FLOAT_EQ(h.distance, 2);
  EXPECT_FALSE(bvh.first_hit({3.25f, 0.25f, 2}, {0, 0, -1}, 1.5f).hit());
  EXPECT_FALSE(bvh.first_hit({3.25f, 0.25f, 2}, {0, 0, 0}).hit());
  EXPECT_FALSE(TriangleBvh(TriangleMesh{}).first_hit({0, 0, 0}, {1, 0, 0}).hit());
}

// closest_point_unless_within: exact beyond the stop distance; within it,
// some triangle that is within it.
TEST(TriangleBvh, SearchEndsAtATriangleWithinTheStopDistance) {
  TriangleMesh m = awkward_mesh();
  TriangleBvh bvh(m);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coord(-3, 8), stop(0, 4);
  int ended = 0, exact = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 p{coord(rng), coord(rng), coord(rng)};
    const float s = stop(rng);
    const float expected = brute_force(m, p);
    const auto hint = i % 2 ? std::uint32_t(rng() % m.triangles.size()) : ClosestPoint::kNone;
    const ClosestPoint c = bvh.closest_point_unless_within(p, s, hint);
    ASSERT_TRUE(c.found());
    if (expected > s) {
      EXPECT_EQ(c.distance_squared, expected) << i;
      ++exact;
    } else {
      EXPECT_LE(c.distance_squared, s) << i;
      ++ended;
    }
    const auto& t = m.triangles[c.triangle];
    EXPECT_NEAR(
        closest_point_on_triangle(p, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]])
            .distance_squared,
        c.distance_squared, 1e-4f);
  }
  // Both kinds of answer were asked for.
  EXPECT_GT(ended, 100);
  EXPECT_GT(exact, 100);
  // A negative stop distance never ends early.
  EXPECT_EQ(bvh.closest_point_unless_within({5, 5, 6}, -1).distance_squared,
            brute_force(m, {5, 5, 6}));
}

TEST(TriangleBvh, QueriesNearTheSurface) {
  TriangleMesh m = test::make_icosphere(4);
  for (BvhBuild build : {BvhBuild::kSah, BvhBuild::kMorton}) {
    TriangleBvh bvh(m, {.build = build});
    EXPECT_GT(bvh.node_count(), 1u);
    EXPECT_LE(bvh.depth(), 60);
    std::mt19937 rng(9);
    std::normal_distribution<float> g(0, 1);
    for (int i = 0; i < 2000; ++i) {
      Vec3 p = normalized(Vec3{g(rng), g(rng), g(rng)}) * (1 + 0.01f * g(rng));
      EXPECT_EQ(bvh.closest_point(p).distance_squared, brute_force(m, p)) << i;
    }
  }
}

TEST(TriangleBvh, EmptyMeshFindsNothing) {
  TriangleMesh m;
  TriangleBvh bvh(m);
  EXPECT_TRUE(bvh.empty());
  EXPECT_FALSE(bvh.closest_point({0, 0, 0}).found());
}

TEST(TriangleBvh, AllCentroidsEqualStillSplits) {
  // Many copies of one triangle: SAH cannot split, the median fallback must.
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (int i = 0; i < 1000; ++i) m.triangles.push_back({0, 1, 2});
  TriangleBvh bvh(m, {.leaf_size = 2});
  EXPECT_LE(bvh.depth(), 12);
  EXPECT_FLOAT_EQ(bvh.closest_point({0.2f, 0.2f, 2}).distance_squared, 4);
  // All Morton codes equal: halved.
  TriangleBvh morton(m, {.leaf_size = 2, .build = BvhBuild::kMorton});
  EXPECT_LE(morton.depth(), 12);
  EXPECT_FLOAT_EQ(morton.closest_point({0.2f, 0.2f, 2}).distance_squared, 4);
}

TEST(TriangleBvh, NormalTieRulePrefersTheCloserNormal) {
  // A point at the cube's corner vertex is equally close to the three faces
  // there; the preferred normal picks among them.
  TriangleMesh m = test::make_cube();
  TriangleBvh bvh(m);
  for (Vec3 n : {Vec3{0, 0, -1}, Vec3{0, -1, 0}, Vec3{-1, 0, 0}}) {
    ClosestPoint c = bvh.closest_point({0, 0, 0}, n);
    EXPECT_EQ(c.distance_squared, 0);
    EXPECT_EQ(bvh.normal_at(c), n);
  }
  // Off the corner along the diagonal, the three faces are again tied.
  ClosestPoint c = bvh.closest_point({-1, -1, -1}, {-1, 0, 0});
  EXPECT_FLOAT_EQ(c.distance_squared, 3);
  EXPECT_EQ(bvh.normal_at(c), (Vec3{-1, 0, 0}));
}

// closest_point_lowest_index: the exact minimum distance, and among the
// triangles at exactly that distance the lowest index, whatever the hint.
TEST(TriangleBvh, LowestIndexTieRuleIgnoresTheHint) {
  // A point at or straight off the cube's corner vertex is equally close to
  // every triangle that shares the vertex.
  TriangleMesh m = test::make_cube();
  TriangleBvh bvh(m, {.leaf_size = 1});
  for (Vec3 p : {Vec3{0, 0, 0}, Vec3{-1, -1, -1}, Vec3{2, 2, 2}}) {
    std::uint32_t lowest = ClosestPoint::kNone;
    const float expected = brute_force(m, p);
    for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
      const auto& f = m.triangles[t];
      if (closest_point_on_triangle(p, m.positions[f[0]], m.positions[f[1]], m.positions[f[2]])
              .distance_squared == expected)
        lowest = std::min(lowest, t);
    }
    for (std::uint32_t hint = 0; hint <= m.triangles.size(); ++hint) {
      const ClosestPoint c =
          bvh.closest_point_lowest_index(p, hint < m.triangles.size() ? hint : ClosestPoint::kNone);
      EXPECT_EQ(c.distance_squared, expected);
      EXPECT_EQ(c.triangle, lowest) << hint;
    }
  }
  // On random queries it agrees with brute force too.
  TriangleMesh awkward = awkward_mesh();
  TriangleBvh tree(awkward, {.build = BvhBuild::kMorton});
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coord(-3, 8);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p{coord(rng), coord(rng), coord(rng)};
    const auto hint = std::uint32_t(rng() % awkward.triangles.size());
    EXPECT_EQ(tree.closest_point_lowest_index(p, hint).distance_squared, brute_force(awkward, p));
  }
}

TEST(TriangleBvh, NormalAtInterpolatesVertexNormals) {
  TriangleMesh m = test::make_square(0, 0, 1, 1);
  m.normals = {{0, 0, 1}, {0, 0, 1}, {1, 0, 0}, {1, 0, 0}};
  TriangleBvh smooth(m);
  ClosestPoint c = smooth.closest_point({0.5f, 0.5f, 1});
  Vec3 n = smooth.normal_at(c);
  EXPECT_NEAR(n.x, std::sqrt(0.5f), 1e-5f);
  EXPECT_NEAR(n.z, std::sqrt(0.5f), 1e-5f);
  TriangleBvh faceted(m, {.vertex_normals = false});
  EXPECT_EQ(faceted.normal_at(faceted.closest_point({0.5f, 0.5f, 1})), (Vec3{0, 0, 1}));
}

}  // namespace
}  // namespace lodforge
