#pragma once
// Small named meshes for the metrics tests.
#include <cmath>
#include <map>
#include <utility>

#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge::test {

/// Axis-aligned cube [0,1]^3 + offset, 8 vertices, 12 outward-facing triangles.
inline TriangleMesh unit_cube(Vec3 offset = {}) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.positions.push_back(Vec3{float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)} + offset);
  }
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

/// Square [x0,x1] x [y0,y1] in the plane z = 0 as two triangles facing +z.
inline TriangleMesh square(float x0, float y0, float x1, float y1) {
  TriangleMesh m;
  m.positions = {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

/// Regular icosahedron with circumradius `radius`, subdivided `level` times
/// (each triangle into four at its edge midpoints, new vertices pushed onto
/// the sphere). Level 0 is the icosahedron itself.
inline TriangleMesh icosphere(int level, float radius = 1) {
  const double phi = (1 + std::sqrt(5.0)) / 2;
  TriangleMesh m;
  double raw[12][3] = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                       {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                       {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  auto on_sphere = [&](double x, double y, double z) {
    double l = std::sqrt(x * x + y * y + z * z);
    return Vec3{float(x / l * radius), float(y / l * radius), float(z / l * radius)};
  };
  for (auto& v : raw) m.positions.push_back(on_sphere(v[0], v[1], v[2]));
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      Vec3 p = m.positions[a] + m.positions[b];
      m.positions.push_back(on_sphere(p.x, p.y, p.z));
      return mid[key] = std::uint32_t(m.positions.size() - 1);
    };
    std::vector<Triangle> next;
    for (const auto& t : m.triangles) {
      std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      next.insert(next.end(), {{t[0], ab, ca}, {t[1], bc, ab}, {t[2], ca, bc}, {ab, bc, ca}});
    }
    m.triangles = std::move(next);
  }
  return m;
}

}  // namespace lodforge::test
