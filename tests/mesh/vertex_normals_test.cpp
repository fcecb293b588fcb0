// Angle-weighted vertex normals.
#include "lodforge/mesh/vertex_normals.h"

#include <gtest/gtest.h>

#include "core/expect_near.h"

#include <cmath>

#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

using test::expect_near;

TEST(VertexNormals, ACubeCornerPointsAlongItsDiagonal) {
  const TriangleMesh cube = test::make_centered_cube(1.f);
  const std::vector<Vec3> n = angle_weighted_normals(cube);
  ASSERT_EQ(n.size(), cube.positions.size());
  // Every corner sees three faces at right angles with equal total angle
  // each, however the faces are split into triangles.
  for (std::size_t i = 0; i < n.size(); ++i) expect_near(n[i], normalized(cube.positions[i]));
}

TEST(VertexNormals, ASoupIsAsSmoothAsTheWeldedMesh) {
  const TriangleMesh sphere = test::make_icosphere(1);
  const TriangleMesh soup = test::as_soup(sphere);
  const std::vector<Vec3> welded = angle_weighted_normals(sphere);
  const std::vector<Vec3> split = angle_weighted_normals(soup);
  for (std::size_t f = 0; f < soup.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k)
      expect_near(split[soup.triangles[f][k]], welded[sphere.triangles[f][k]]);
  // An icosphere's vertices lie on the unit sphere: the normal is close to
  // the position (the neighbourhoods are nearly symmetric).
  for (std::size_t i = 0; i < welded.size(); ++i) {
    EXPECT_NEAR(length(welded[i]), 1.f, 1e-5f);
    EXPECT_GT(dot(welded[i], normalized(sphere.positions[i])), 0.999f);
  }
}

TEST(VertexNormals, AFlatGridFacesUpAndDegenerateTrianglesGiveZero) {
  for (const Vec3& n : angle_weighted_normals(test::make_grid(3))) expect_near(n, {0, 0, 1});
  TriangleMesh line;
  line.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  line.triangles = {{0, 1, 2}};
  for (const Vec3& n : angle_weighted_normals(line)) EXPECT_EQ(n, (Vec3{}));
}

}  // namespace
}  // namespace lodforge
