#pragma once
/// The exact closest point of a triangle to a query point, with the
/// barycentric coordinates of that point so attributes (normals, colours) can
/// be interpolated there.
#include <array>

#include "lodforge/core/math.h"

namespace lodforge {

/// Where on a triangle (a, b, c) the closest point lies.
struct TrianglePoint {
  Vec3 point;                          ///< the closest point itself
  std::array<float, 3> barycentric{};  ///< weights of a, b, c; >= 0, sum 1
  float distance_squared = 0;          ///< |query - point|^2
};

/// Closest point of the solid triangle (a, b, c) to `p` (Ericson's Voronoi
/// region method). Degenerate triangles are handled: a triangle whose vertices
/// are collinear (or coincide) is treated as the segment (or point) it spans,
/// so the result is always finite for finite input. Never throws.
TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace lodforge
