// Synthetic range scans: an orthographic z-buffer per view. Rasterising the
// triangles into the grid gives exactly the nearest ray hit at every grid
// point (each pixel centre is a ray along -z; its hit on a triangle is the
// barycentric interpolation of the projected corners), without a ray-casting
// acceleration structure.
#include "lodforge/mcoctree/scan_mesh.h"

#include <fmt/core.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "lodforge/core/error.h"

namespace lodforge {
namespace {

// Quaternion (x, y, z, w) of the rotation whose matrix has columns u, v, w.
std::array<float, 4> quaternion(const Vec3& u, const Vec3& v, const Vec3& w) {
  double m[3][3] = {{u.x, v.x, w.x}, {u.y, v.y, w.y}, {u.z, v.z, w.z}};
  double tr = m[0][0] + m[1][1] + m[2][2], x, y, z, s;
  double qw;
  if (tr > 0) {
    s = std::sqrt(tr + 1.0) * 2;
    qw = 0.25 * s, x = (m[2][1] - m[1][2]) / s, y = (m[0][2] - m[2][0]) / s,
    z = (m[1][0] - m[0][1]) / s;
  } else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
    s = std::sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2;
    qw = (m[2][1] - m[1][2]) / s, x = 0.25 * s, y = (m[0][1] + m[1][0]) / s,
    z = (m[0][2] + m[2][0]) / s;
  } else if (m[1][1] > m[2][2]) {
    s = std::sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2;
    qw = (m[0][2] - m[2][0]) / s, x = (m[0][1] + m[1][0]) / s, y = 0.25 * s,
    z = (m[1][2] + m[2][1]) / s;
  } else {
    s = std::sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2;
    qw = (m[1][0] - m[0][1]) / s, x = (m[0][2] + m[2][0]) / s, y = (m[1][2] + m[2][1]) / s,
    z = 0.25 * s;
  }
  return {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z),
          static_cast<float>(qw)};
}

}  // namespace

std::vector<RangeScan> scan_mesh(const TriangleMesh& mesh, const ScanOptions& options) {
  if (options.views < 1 || options.views > 1000) throw DataError("scan: views must be in 1..1000");
  if (options.resolution < 4 || options.resolution > 4096)
    throw DataError("scan: resolution must be in 4..4096");
  if (mesh.triangles.empty()) throw DataError("scan: the mesh has no triangles");
  for (const auto& p : mesh.positions)
    if (!is_finite(p)) throw DataError("scan: the mesh has a non-finite coordinate");
  const Box3 box = mesh.bounds();
  const Vec3 centre = box.center();
  const float radius = std::max(box.diagonal() * 0.5f, 1e-20f);
  const int res = options.resolution;
  const float spacing = 2 * radius / static_cast<float>(res);
  const bool colored = mesh.has_colors();
  std::vector<RangeScan> scans;
  std::vector<float> depth;
  std::vector<std::uint32_t> hit_triangle;
  std::vector<Vec3> hit_bary;
  std::vector<Vec3> local(mesh.positions.size());
  for (int k = 0; k < options.views; ++k) {
    // Fibonacci lattice on the sphere: the direction towards the sensor.
    double zc = options.views == 1 ? 1.0 : 1.0 - 2.0 * (k + 0.5) / options.views;
    double phi = k * kPi * (3.0 - std::sqrt(5.0));
    double rxy = std::sqrt(std::max(0.0, 1.0 - zc * zc));
    Vec3 w{static_cast<float>(rxy * std::cos(phi)), static_cast<float>(rxy * std::sin(phi)),
           static_cast<float>(zc)};
    Vec3 up = std::abs(w.y) < 0.9f ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
    Vec3 u = normalized(cross(up, w)), v = cross(w, u);
    for (std::size_t i = 0; i < local.size(); ++i) {
      Vec3 d = mesh.positions[i] - centre;
      local[i] = {dot(d, u), dot(d, v), dot(d, w)};
    }
    depth.assign(static_cast<std::size_t>(res) * res, -std::numeric_limits<float>::infinity());
    hit_triangle.assign(depth.size(), UINT32_MAX);
    hit_bary.assign(depth.size(), Vec3{});
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& f = mesh.triangles[t];
      const Vec3 &a = local[f[0]], &b = local[f[1]], &c = local[f[2]];
      float area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
      if (!(std::abs(area) > 0)) continue;  // edge-on: no ray hits it
      auto pixel = [&](float x) { return (x + radius) / spacing - 0.5f; };
      int c0 = std::max(0, static_cast<int>(std::ceil(pixel(std::min({a.x, b.x, c.x})))));
      int c1 = std::min(res - 1, static_cast<int>(std::floor(pixel(std::max({a.x, b.x, c.x})))));
      int r0 = std::max(0, static_cast<int>(std::ceil(pixel(std::min({a.y, b.y, c.y})))));
      int r1 = std::min(res - 1, static_cast<int>(std::floor(pixel(std::max({a.y, b.y, c.y})))));
      for (int r = r0; r <= r1; ++r)
        for (int col = c0; col <= c1; ++col) {
          float x = -radius + (static_cast<float>(col) + 0.5f) * spacing;
          float y = -radius + (static_cast<float>(r) + 0.5f) * spacing;
          float l1 = ((c.x - x) * (a.y - y) - (a.x - x) * (c.y - y)) / area;  // weight of b
          float l2 = ((a.x - x) * (b.y - y) - (b.x - x) * (a.y - y)) / area;  // weight of c
          float l0 = 1 - l1 - l2;
          if (l0 < 0 || l1 < 0 || l2 < 0) continue;
          float z = l0 * a.z + l1 * b.z + l2 * c.z;
          std::size_t px = static_cast<std::size_t>(r) * res + col;
          if (z > depth[px]) depth[px] = z, hit_triangle[px] = t, hit_bary[px] = {l0, l1, l2};
        }
    }
    RangeScan s;
    s.name = fmt::format("scan{:03}.ply", k);
    s.cols = s.rows = res;
    s.grid.assign(depth.size(), -1);
    s.translation = centre;
    auto q = quaternion(u, v, w);
    s.rotation = {-q[0], -q[1], -q[2], q[3]};  // .conf convention: see range_scan.h
    for (int r = 0; r < res; ++r)
      for (int col = 0; col < res; ++col) {
        std::size_t px = static_cast<std::size_t>(r) * res + col;
        if (hit_triangle[px] == UINT32_MAX) continue;
        s.grid[px] = static_cast<std::int32_t>(s.points.size());
        s.points.push_back({-radius + (static_cast<float>(col) + 0.5f) * spacing,
                            -radius + (static_cast<float>(r) + 0.5f) * spacing, depth[px]});
        if (colored) {
          const auto& f = mesh.triangles[hit_triangle[px]];
          Vec3 col3 = mesh.colors[f[0]] * hit_bary[px].x + mesh.colors[f[1]] * hit_bary[px].y +
                      mesh.colors[f[2]] * hit_bary[px].z;
          Rgb8 rgb;
          for (int a = 0; a < 3; ++a)
            rgb[a] = static_cast<std::uint8_t>(std::lround(std::clamp(col3[a], 0.0f, 1.0f) * 255));
          s.colors.push_back(rgb);
        }
      }
    scans.push_back(std::move(s));
  }
  return scans;
}

}  // namespace lodforge
