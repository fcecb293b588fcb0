#pragma once
/// Small named meshes built in code, for the tests of every module.
///
/// All closed meshes are consistently oriented with outward normals
/// (counter-clockwise seen from outside). Counts are given per builder so that
/// tests can assert them.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <unordered_map>
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge::test {

/// Regular-ish tetrahedron: 4 vertices, 4 triangles, closed, genus 0.
inline TriangleMesh make_tetrahedron() {
  TriangleMesh m;
  m.positions = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  m.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  return m;
}

/// Axis-aligned cube [0,size]^3 + offset: 8 vertices, 12 triangles, closed,
/// genus 0.
inline TriangleMesh make_cube(float size = 1.0f, Vec3 offset = {}) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.push_back(
        offset + Vec3{(i & 1) ? size : 0.0f, (i & 2) ? size : 0.0f, (i & 4) ? size : 0.0f});
  // Quads as (a, b, c, d) counter-clockwise from outside.
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

/// Axis-aligned cube [-half, half]^3 around `center`.
inline TriangleMesh make_centered_cube(float half = 1.0f, Vec3 center = {}) {
  return make_cube(2 * half, center - Vec3{half, half, half});
}

/// Square [x0,x1] x [y0,y1] in the plane z = 0 as two triangles facing +z.
inline TriangleMesh make_square(float x0, float y0, float x1, float y1) {
  TriangleMesh m;
  m.positions = {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

/// Planar grid of n x n quads in z = 0 over [0,1]^2, normals +z, texcoords =
/// (x, y): (n+1)^2 vertices, 2 n^2 triangles, one boundary loop of 4n edges.
inline TriangleMesh make_grid(int n) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      float x = static_cast<float>(i) / n, y = static_cast<float>(j) / n;
      m.positions.push_back({x, y, 0});
      m.normals.push_back({0, 0, 1});
      m.texcoords.push_back({x, y});
    }
  auto id = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

/// Open disk (a fan) of radius 1 in z = 0 facing +z: 1 + segments vertices,
/// `segments` triangles, one boundary loop.
inline TriangleMesh make_open_disk(int segments = 16) {
  TriangleMesh m;
  m.positions.push_back({0, 0, 0});
  for (int i = 0; i < segments; ++i) {
    double a = 2 * kPi * i / segments;
    m.positions.push_back({static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0});
  }
  for (int i = 0; i < segments; ++i)
    m.triangles.push_back(
        {0, static_cast<std::uint32_t>(1 + i), static_cast<std::uint32_t>(1 + (i + 1) % segments)});
  return m;
}

/// UV sphere of radius r with unit normals and texcoords: 2 poles plus
/// (stacks-1) rings of `slices` vertices, 2 * slices * (stacks-1) triangles,
/// closed (no seam vertices: texcoord u wraps).
inline TriangleMesh make_uv_sphere(int slices = 16, int stacks = 8, float r = 1.0f) {
  TriangleMesh m;
  auto add = [&](double theta, double phi) {
    Vec3 n{static_cast<float>(std::sin(theta) * std::cos(phi)),
           static_cast<float>(std::sin(theta) * std::sin(phi)),
           static_cast<float>(std::cos(theta))};
    m.positions.push_back(n * r);
    m.normals.push_back(n);
    m.texcoords.push_back(
        {static_cast<float>(phi / (2 * kPi)), static_cast<float>(1 - theta / kPi)});
  };
  add(0, 0);
  for (int s = 1; s < stacks; ++s)
    for (int i = 0; i < slices; ++i) add(kPi * s / stacks, 2 * kPi * i / slices);
  add(kPi, 0);
  auto ring = [&](int s, int i) {
    return static_cast<std::uint32_t>(1 + (s - 1) * slices + i % slices);
  };
  auto south = static_cast<std::uint32_t>(m.positions.size() - 1);
  for (int i = 0; i < slices; ++i) m.triangles.push_back({0, ring(1, i), ring(1, i + 1)});
  for (int s = 1; s + 1 < stacks; ++s)
    for (int i = 0; i < slices; ++i) {
      m.triangles.push_back({ring(s, i), ring(s + 1, i), ring(s + 1, i + 1)});
      m.triangles.push_back({ring(s, i), ring(s + 1, i + 1), ring(s, i + 1)});
    }
  for (int i = 0; i < slices; ++i)
    m.triangles.push_back({ring(stacks - 1, i), south, ring(stacks - 1, i + 1)});
  return m;
}

/// Icosphere of radius `radius`: 12 vertices and 20 triangles at subdiv 0;
/// each subdivision multiplies the triangles by 4 (V = 10 * 4^s + 2).
inline TriangleMesh make_icosphere(int subdiv = 1, float radius = 1.0f) {
  TriangleMesh m;
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  Vec3 p[12] = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (const Vec3& v : p) m.positions.push_back(normalized(v));
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int s = 0; s < subdiv; ++s) {
    std::vector<Triangle> next;
    std::unordered_map<std::uint64_t, std::uint32_t> mids;
    auto mid = [&](std::uint32_t a, std::uint32_t b) {
      std::uint64_t key = (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
      auto [it, inserted] = mids.try_emplace(key, static_cast<std::uint32_t>(m.positions.size()));
      if (inserted) m.positions.push_back(normalized(m.positions[a] + m.positions[b]));
      return it->second;
    };
    for (const Triangle& f : m.triangles) {
      std::uint32_t a = mid(f[0], f[1]), b = mid(f[1], f[2]), c = mid(f[2], f[0]);
      next.insert(next.end(), {{f[0], a, c}, {f[1], b, a}, {f[2], c, b}, {a, b, c}});
    }
    m.triangles = std::move(next);
  }
  if (radius != 1.0f)
    for (Vec3& p : m.positions) p *= radius;
  return m;
}

/// An icosphere (subdivision 4) with every vertex moved in or out by up to 3 %
/// of the radius, deterministically for a seed: a closed surface with detail
/// at every scale, for simplification and measurement tests.
inline TriangleMesh make_bumpy_sphere(unsigned seed) {
  TriangleMesh m = make_icosphere(4);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> bump(0.97f, 1.03f);
  for (Vec3& p : m.positions) p *= bump(rng);
  return m;
}

/// Torus around z with radii R (ring) and r (tube): major * minor vertices,
/// 2 * major * minor triangles, closed, genus 1 (Euler characteristic 0).
inline TriangleMesh make_torus(float R = 1.0f, float r = 0.25f, int major = 24, int minor = 12) {
  TriangleMesh m;
  for (int i = 0; i < major; ++i)
    for (int j = 0; j < minor; ++j) {
      double u = 2 * kPi * i / major, v = 2 * kPi * j / minor;
      double w = R + r * std::cos(v);
      m.positions.push_back({static_cast<float>(w * std::cos(u)),
                             static_cast<float>(w * std::sin(u)),
                             static_cast<float>(r * std::sin(v))});
    }
  auto id = [&](int i, int j) {
    return static_cast<std::uint32_t>((i % major) * minor + j % minor);
  };
  for (int i = 0; i < major; ++i)
    for (int j = 0; j < minor; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

/// UV sphere of radius r: `rings` latitude bands, `segments` longitude bands.
/// Like many real meshes it repeats vertices: a ring of copies at each pole and
/// a seam at longitude 0, at exactly equal positions.
inline TriangleMesh make_seamed_sphere(float r = 1, int rings = 24, int segments = 48) {
  TriangleMesh m;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i <= rings; ++i) {
    const double theta = pi * i / rings;  // from +Y down
    const double ring_r = (i == 0 || i == rings) ? 0 : r * std::sin(theta);
    for (int j = 0; j <= segments; ++j) {
      const double phi = 2 * pi * (j % segments) / segments;
      m.positions.push_back({static_cast<float>(ring_r * std::sin(phi)),
                             static_cast<float>(r * std::cos(theta)),
                             static_cast<float>(ring_r * std::cos(phi))});
    }
  }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * (segments + 1) + j); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      if (i > 0) m.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
      if (i < rings - 1) m.triangles.push_back({at(i, j + 1), at(i + 1, j), at(i + 1, j + 1)});
    }
  return m;
}

/// Cube [0,1]^3 whose faces are n x n grids of quads (2 triangles each), with
/// shared edge and corner vertices: 6 n^2 + 2 vertices, 12 n^2 triangles.
inline TriangleMesh make_subdivided_cube(int n) {
  TriangleMesh m;
  std::map<std::array<int, 3>, std::uint32_t> index;
  auto vertex = [&](std::array<int, 3> g) {
    auto [it, inserted] = index.try_emplace(g, static_cast<std::uint32_t>(m.positions.size()));
    if (inserted) m.positions.push_back({float(g[0]) / n, float(g[1]) / n, float(g[2]) / n});
    return it->second;
  };
  // Each face: origin corner, two in-face axes (u x v = outward normal).
  struct Face {
    std::array<int, 3> o, u, v;
  };
  const Face faces[6] = {{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},
                         {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}},
                         {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  for (const Face& f : faces) {
    auto at = [&](int i, int j) {
      std::array<int, 3> g;
      for (int c = 0; c < 3; ++c) g[c] = f.o[c] * n + f.u[c] * i + f.v[c] * j;
      return vertex(g);
    };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  return m;
}

/// The same surface as a triangle soup: three vertices of its own per
/// triangle, in triangle order, or (reversed) with the vertex list in reverse
/// order, so that the first vertex at a coordinate is another one.
inline TriangleMesh as_soup(const TriangleMesh& m, bool reversed = false) {
  TriangleMesh s;
  for (const auto& t : m.triangles) {
    const auto base = static_cast<std::uint32_t>(s.positions.size());
    for (auto i : t) s.positions.push_back(m.positions[i]);
    s.triangles.push_back({base, base + 1, base + 2});
  }
  if (reversed) {
    const auto last = static_cast<std::uint32_t>(s.positions.size() - 1);
    std::reverse(s.positions.begin(), s.positions.end());
    for (auto& t : s.triangles)
      for (auto& v : t) v = last - v;
  }
  return s;
}

/// Gives every vertex one colour.
inline TriangleMesh with_color(TriangleMesh m, Vec3 rgb) {
  m.colors.assign(m.positions.size(), rgb);
  return m;
}

/// Signed volume of a closed mesh (positive when oriented outward).
inline double signed_volume(const TriangleMesh& m) {
  double v = 0;
  for (const Triangle& t : m.triangles)
    v += dot(m.positions[t[0]], cross(m.positions[t[1]], m.positions[t[2]])) / 6.0;
  return v;
}

}  // namespace lodforge::test
