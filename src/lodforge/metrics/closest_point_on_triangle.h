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

/// A triangle with what every query of it needs computed once: its edge
/// vectors' dot products and whether it is degenerate. For many queries of
/// one triangle (a search structure's leaves).
struct PreparedTriangle {
  Vec3 a, b, c;
  float ab_ab = 0, ab_ac = 0, ac_ac = 0;  ///< dot products of ab = b - a and ac = c - a
  bool degenerate = false;                ///< collinear or coincident corners

  static PreparedTriangle of(const Vec3& a, const Vec3& b, const Vec3& c);
};

/// As closest_point_on_triangle(p, t.a, t.b, t.c), with two dot products of
/// `p` instead of six.
TrianglePoint closest_point_on_triangle(const Vec3& p, const PreparedTriangle& t);

/// Closest point of the solid triangle (a, b, c) to `p` (Ericson's Voronoi
/// region method). Degenerate triangles are handled: a triangle whose vertices
/// are collinear (or coincide) is treated as the segment (or point) it spans,
/// so the result is always finite for finite input. Never throws.
TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace lodforge
