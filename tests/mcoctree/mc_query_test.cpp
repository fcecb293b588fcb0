#include "lodforge/mcoctree/mc_query.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include "lodforge/core/error.h"
#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/metrics/closest_point_on_triangle.h"
#include "mcoctree/capped_model.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

const std::string kBunny = std::string(LODFORGE_SHARED_DATA) + "/meshes/bun_zipper.ply";

// ---- Brute force over every triangle, written independently of mc_query.cpp.

// First hit: the plane's t, then the hit point inside the triangle by the
// signs of the three edge functions (double precision). Negative: no hit.
double brute_ray(const TriangleMesh& m, Vec3 o, Vec3 dir) {
  const Vec3 d = normalized(dir);
  double best = -1;
  for (const auto& f : m.triangles) {
    const Vec3 &a = m.positions[f[0]], &b = m.positions[f[1]], &c = m.positions[f[2]];
    const double ab[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
    const double ac[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
    const double n[3] = {ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2],
                         ab[0] * ac[1] - ab[1] * ac[0]};
    const double nd = n[0] * d.x + n[1] * d.y + n[2] * d.z;
    if (nd == 0) continue;
    const double t =
        (n[0] * (double(a.x) - o.x) + n[1] * (double(a.y) - o.y) + n[2] * (double(a.z) - o.z)) / nd;
    if (t < 0 || (best >= 0 && t >= best)) continue;
    const double x[3] = {o.x + t * d.x, o.y + t * d.y, o.z + t * d.z};
    const Vec3* v[3] = {&a, &b, &c};
    bool inside = true;
    for (int k = 0; k < 3 && inside; ++k) {
      const Vec3 &p = *v[k], &q = *v[(k + 1) % 3];
      const double e[3] = {double(q.x) - p.x, double(q.y) - p.y, double(q.z) - p.z};
      const double w[3] = {x[0] - p.x, x[1] - p.y, x[2] - p.z};
      const double cr[3] = {e[1] * w[2] - e[2] * w[1], e[2] * w[0] - e[0] * w[2],
                            e[0] * w[1] - e[1] * w[0]};
      inside = cr[0] * n[0] + cr[1] * n[1] + cr[2] * n[2] >= 0;
    }
    if (inside) best = t;
  }
  return best;
}

double brute_distance(const TriangleMesh& m, Vec3 p) {
  float best = std::numeric_limits<float>::infinity();
  for (const auto& f : m.triangles)
    best = std::min(
        best, closest_point_on_triangle(p, m.positions[f[0]], m.positions[f[1]], m.positions[f[2]])
                  .distance_squared);
  return std::sqrt(best);
}

// Generalised winding number (sum of the triangles' solid angles, Van
// Oosterom & Strackee 1983): 1 inside a closed outward-wound surface, 0 outside.
double winding_number(const TriangleMesh& m, Vec3 p) {
  double sum = 0;
  for (const auto& f : m.triangles) {
    double v[3][3];
    double len[3];
    for (int k = 0; k < 3; ++k) {
      const Vec3& q = m.positions[f[k]];
      v[k][0] = double(q.x) - p.x, v[k][1] = double(q.y) - p.y, v[k][2] = double(q.z) - p.z;
      len[k] = std::sqrt(v[k][0] * v[k][0] + v[k][1] * v[k][1] + v[k][2] * v[k][2]);
    }
    auto dotd = [](const double* a, const double* b) {
      return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    };
    const double bc[3] = {v[1][1] * v[2][2] - v[1][2] * v[2][1],
                          v[1][2] * v[2][0] - v[1][0] * v[2][2],
                          v[1][0] * v[2][1] - v[1][1] * v[2][0]};
    const double num = dotd(v[0], bc);
    const double den = len[0] * len[1] * len[2] + dotd(v[0], v[1]) * len[2] +
                       dotd(v[1], v[2]) * len[0] + dotd(v[2], v[0]) * len[1];
    sum += 2 * std::atan2(num, den);
  }
  return sum / (4 * kPi);
}

Box3 bounds(const TriangleMesh& m) {
  Box3 b;
  for (auto p : m.positions) b.add(p);
  return b;
}

// Random query points in the box grown by a fifth of its diagonal.
Vec3 random_point(std::mt19937& rng, const Box3& b, float grow) {
  std::uniform_real_distribution<float> u(0, 1);
  Vec3 lo = b.lo - Vec3{grow, grow, grow}, hi = b.hi + Vec3{grow, grow, grow};
  return {lo.x + u(rng) * (hi.x - lo.x), lo.y + u(rng) * (hi.y - lo.y),
          lo.z + u(rng) * (hi.z - lo.z)};
}

struct Agreement {
  int hits = 0, inside = 0, near_surface = 0;
};

// `rays` random rays (half aimed at a point of the box, so most hit) and as
// many random points against brute force over `mesh`, to 1e-5 of the
// diagonal: hit or miss, hit distance, closest distance, and the side (the
// winding number's, for points farther than the tolerance from the surface).
void check_against_brute_force(const McQuery& q, const TriangleMesh& mesh, int count, unsigned seed,
                               Agreement& a) {
  const Box3 box = bounds(mesh);
  const float diag = box.diagonal(), tol = 1e-5f * diag;
  std::mt19937 rng(seed);
  std::normal_distribution<float> g;
  for (int i = 0; i < count; ++i) {
    const Vec3 o = random_point(rng, box, 0.2f * diag);
    const Vec3 d = i % 2 ? random_point(rng, box, 0) - o : Vec3{g(rng), g(rng), g(rng)};
    const McRayHit hit = q.ray(o, d);
    const double expect = brute_ray(mesh, o, d);
    ASSERT_EQ(hit.hit(), expect >= 0) << "ray " << i;
    if (!hit.hit()) continue;
    ++a.hits;
    ASSERT_NEAR(hit.distance, expect, tol) << "ray " << i;
    EXPECT_NEAR(length(hit.point - (o + normalized(d) * hit.distance)), 0, tol);
    EXPECT_NEAR(length(hit.normal), 1, 1e-5);
  }
  for (int i = 0; i < count; ++i) {
    const Vec3 p = random_point(rng, box, 0.2f * diag);
    const McClosest c = q.closest(p);
    const double expect = brute_distance(mesh, p);
    ASSERT_TRUE(c.found());
    ASSERT_FALSE(c.open) << "point " << i;
    ASSERT_NEAR(std::abs(c.distance), expect, tol) << "point " << i;
    EXPECT_NEAR(length(c.point - p), expect, tol);
    EXPECT_EQ(q.inside(p), c.distance < 0);
    if (expect <= tol) {
      ++a.near_surface;
      continue;
    }
    const bool inside = winding_number(mesh, p) > 0.5;
    ASSERT_EQ(c.inside(), inside) << "point " << i << " at " << c.distance;
    a.inside += inside;
  }
}

// A unit cube at resolution 16: a ray at a face's centre hits it one unit
// away with the face's outward normal; the other way, or stopped short, it
// misses; the centre is inside at about half a unit.
TEST(McQuery, CubeRaysAndPoints) {
  const McLodModel m = model_of(test::make_cube(), 16);
  McQuery made(m);
  const McQuery q = std::move(made);  // movable: answers from its own copies
  const float h = m.cell_size;
  McRayHit hit = q.ray({0.5f, 0.5f, -1}, {0, 0, 2});
  ASSERT_TRUE(hit.hit());
  EXPECT_NEAR(hit.distance, 1, h);
  EXPECT_NEAR(hit.point.z, 0, h);
  EXPECT_NEAR(hit.normal.z, -1, 1e-3);
  EXPECT_FALSE(q.ray({0.5f, 0.5f, -1}, {0, 0, -1}).hit());
  EXPECT_FALSE(q.ray({0.5f, 0.5f, -1}, {0, 0, 1}, 0.5f).hit());
  // From inside: the far face, seen from behind.
  hit = q.ray({0.5f, 0.5f, 0.5f}, {1, 0, 0});
  ASSERT_TRUE(hit.hit());
  EXPECT_NEAR(hit.distance, 0.5f, h);
  EXPECT_NEAR(hit.normal.x, 1, 1e-3);

  McClosest c = q.closest({0.5f, 0.5f, 0.5f});
  ASSERT_TRUE(c.found());
  EXPECT_NEAR(c.distance, -0.5f, h);
  EXPECT_TRUE(q.inside({0.5f, 0.5f, 0.5f}));
  c = q.closest({0.5f, 0.5f, 3});
  EXPECT_NEAR(c.distance, 2, h);
  EXPECT_NEAR(c.point.z, 1, h);
  EXPECT_FALSE(q.inside({0.5f, 0.5f, 3}));
  EXPECT_FALSE(q.inside({-0.1f, 0.5f, 0.5f}));
}

TEST(McQuery, BadInputThrows) {
  const McQuery q(model_of(test::make_tetrahedron(), 8));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_THROW(q.ray({0, 0, 0}, {0, 0, 0}), DataError);
  EXPECT_THROW(q.ray({nan, 0, 0}, {1, 0, 0}), DataError);
  EXPECT_THROW(q.ray({0, 0, 0}, {inf, 0, 0}), DataError);
  EXPECT_THROW(q.closest({0, inf, 0}), DataError);
  EXPECT_THROW(q.inside({0, 0, nan}), DataError);
  const McLodModel m = model_of(test::make_tetrahedron(), 8);
  EXPECT_THROW(McQuery(m, {.priority = 1, .percent = 50}), DataError);
}

// A model without cells (nothing read): no hits, nothing found, outside.
TEST(McQuery, EmptyModel) {
  const McQuery q(McLodModel{});
  EXPECT_EQ(q.node_count(), 0u);
  EXPECT_FALSE(q.ray({0, 0, 0}, {1, 0, 0}).hit());
  EXPECT_FALSE(q.closest({0, 0, 0}).found());
  EXPECT_FALSE(q.inside({0, 0, 0}));
}

// The query's level is extract_mc_mesh's, triangle for triangle.
TEST(McQuery, LevelIsTheExtractedMesh) {
  const McLodModel m = model_of(test::make_torus(), 24);
  for (double pct : {100.0, 30.0, 1.0}) {
    const McQuery q(m, {.percent = pct});
    const auto r = extract_mc_mesh(m, {.percent = pct});
    EXPECT_EQ(q.priority(), r.priority);
    EXPECT_EQ(q.mesh().triangles, r.mesh.triangles);
    EXPECT_EQ(q.mesh().positions, r.mesh.positions);
  }
}

// A torus (closed, with a hole through it, so rays and points meet concave
// and convex parts): 10 000 random rays and points against brute force.
TEST(McQuery, TorusAgreesWithBruteForce) {
  const McLodModel m = model_of(test::make_torus(1, 0.35f, 48, 24), 40);
  const McQuery q(m);
  const TriangleMesh mesh = extract_mc_mesh(m).mesh;
  Agreement a;
  check_against_brute_force(q, mesh, 10000, 1, a);
  std::printf("torus: %zu triangles, %zu nodes, %d hits, %d inside, %d near the surface\n",
              mesh.triangle_count(), q.node_count(), a.hits, a.inside, a.near_surface);
  EXPECT_GT(a.hits, 3000);
  EXPECT_GT(a.inside, 100);
}

// The bunny (capped, so closed) at resolution 64: 10 000 random rays and
// points at full resolution, and 2 000 at a coarse level (5 % of the
// triangles) against brute force over that level's mesh.
TEST(McQuery, BunnyAgreesWithBruteForce) {
  if (!std::filesystem::exists(kBunny)) GTEST_SKIP() << kBunny << " missing";
  const McLodModel m = model_of(read_mesh(kBunny), 64);
  const McQuery full(m);
  const TriangleMesh mesh = extract_mc_mesh(m).mesh;
  Agreement a;
  check_against_brute_force(full, mesh, 10000, 2, a);
  std::printf("bunny: %zu triangles, %zu nodes, %d hits, %d inside, %d near the surface\n",
              mesh.triangle_count(), full.node_count(), a.hits, a.inside, a.near_surface);
  EXPECT_GT(a.hits, 3000);
  EXPECT_GT(a.inside, 100);

  const McQuery coarse(m, {.percent = 5});
  const auto level = extract_mc_mesh(m, {.percent = 5});
  ASSERT_LT(level.priority, m.priorities());
  ASSERT_LT(level.mesh.triangle_count(), mesh.triangle_count() / 10);
  a = {};
  check_against_brute_force(coarse, level.mesh, 2000, 3, a);
  std::printf("bunny at 5 %%: %zu triangles, %d hits, %d inside\n", level.mesh.triangle_count(),
              a.hits, a.inside);
  EXPECT_GT(a.hits, 600);
}

// The bunny as built (McHoles::kOpen: holes in its base): points nearest the
// borders report an unknown side and count as outside.
TEST(McQuery, OpenBordersAreReported) {
  if (!std::filesystem::exists(kBunny)) GTEST_SKIP() << kBunny << " missing";
  const McLodModel m = compile_mc_lod(build_mc_octree(read_mesh(kBunny), {.resolution = 32}).tree);
  const McQuery q(m);
  const Box3 box = bounds(q.mesh());
  std::mt19937 rng(4);
  int open = 0;
  for (int i = 0; i < 2000; ++i) {
    const McClosest c = q.closest(random_point(rng, box, 0.2f * box.diagonal()));
    if (!c.open) continue;
    ++open;
    EXPECT_GE(c.distance, 0);
    EXPECT_FALSE(c.inside());
  }
  EXPECT_GT(open, 0);
}

}  // namespace
}  // namespace lodforge
