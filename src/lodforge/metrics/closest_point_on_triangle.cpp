// Closest point on a triangle by Voronoi regions: C. Ericson, "Real-Time
// Collision Detection", Morgan Kaufmann 2005, §5.1.5 ("Closest Point on
// Triangle to Point"). The point is located in one of the seven feature
// regions (three vertices, three edges, the face) with a handful of dot
// products, without computing the projection onto the plane first; each
// region yields the closest point and its barycentric coordinates directly.
//
// Ericson's face branch divides by the triangle's (doubled, squared) area.
// For a degenerate triangle that area is zero or rounding noise, so such
// triangles are detected up front, by the size of the cross product relative
// to the edge lengths, and treated as their longest edge (a collinear triangle
// is exactly the segment between its two farthest vertices).
#include "lodforge/metrics/closest_point_on_triangle.h"

#include <algorithm>

namespace lodforge {
namespace {

// |ab x ac|^2 <= kDegenerate * |ab|^2 |ac|^2 means sin^2 of the angle at a is
// below 1e-12: the triangle is a sliver narrower than float resolution.
constexpr float kDegenerate = 1e-12f;

TrianglePoint make(const Vec3& p, const Vec3& q, float wa, float wb, float wc) {
  return {q, {wa, wb, wc}, length_squared(p - q)};
}

// Closest point on segment (x, y) of a degenerate triangle; `ix`, `iy` are the
// corner indices (0..2) of x and y, so the weights land in the right slots.
TrianglePoint closest_on_segment(const Vec3& p, const Vec3& x, const Vec3& y, int ix, int iy) {
  Vec3 d = y - x;
  float dd = dot(d, d);
  float t = dd > 0 ? std::clamp(dot(p - x, d) / dd, 0.f, 1.f) : 0.f;
  std::array<float, 3> w{};
  w[ix] = 1 - t;
  w[iy] += t;
  Vec3 q = x + d * t;
  return {q, w, length_squared(p - q)};
}

TrianglePoint closest_on_degenerate(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  float ab = length_squared(b - a), bc = length_squared(c - b), ca = length_squared(a - c);
  if (ab >= bc && ab >= ca) return closest_on_segment(p, a, b, 0, 1);
  if (bc >= ca) return closest_on_segment(p, b, c, 1, 2);
  return closest_on_segment(p, c, a, 2, 0);
}

}  // namespace

PreparedTriangle PreparedTriangle::of(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a;
  const Vec3 n = cross(ab, ac);
  return {.a = a,
          .b = b,
          .c = c,
          .ab_ab = dot(ab, ab),
          .ab_ac = dot(ab, ac),
          .ac_ac = dot(ac, ac),
          .degenerate = length_squared(n) <= kDegenerate * length_squared(ab) * length_squared(ac)};
}

TrianglePoint closest_point_on_triangle(const Vec3& p, const PreparedTriangle& t) {
  if (t.degenerate) return closest_on_degenerate(p, t.a, t.b, t.c);
  const Vec3 &a = t.a, &b = t.b, &c = t.c;
  const Vec3 ab = b - a, ac = c - a;
  // Region tests, in Ericson's order, with d3..d6 (the dot products of ab and
  // ac with p - b and p - c) from d1, d2 and the edges' own dot products:
  //   vertex A  : d1 <= 0, d2 <= 0
  //   vertex B  : d3 >= 0, d4 <= d3
  //   edge AB   : vc <= 0, d1 >= 0, d3 <= 0
  //   vertex C  : d6 >= 0, d5 <= d6
  //   edge AC   : vb <= 0, d2 >= 0, d6 <= 0
  //   edge BC   : va <= 0, d4 - d3 >= 0, d5 - d6 >= 0
  //   face      : otherwise
  const Vec3 ap = p - a;
  const float d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return make(p, a, 1, 0, 0);

  const float d3 = d1 - t.ab_ab, d4 = d2 - t.ab_ac;
  if (d3 >= 0 && d4 <= d3) return make(p, b, 0, 1, 0);

  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    float v = d1 / (d1 - d3);
    return make(p, a + ab * v, 1 - v, v, 0);
  }

  const float d5 = d1 - t.ab_ac, d6 = d2 - t.ac_ac;
  if (d6 >= 0 && d5 <= d6) return make(p, c, 0, 0, 1);

  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    float w = d2 / (d2 - d6);
    return make(p, a + ac * w, 1 - w, 0, w);
  }

  const float va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return make(p, b + (c - b) * w, 0, 1 - w, w);
  }

  const float denom = 1 / (va + vb + vc);
  const float v = vb * denom, w = vc * denom;
  return make(p, a + ab * v + ac * w, 1 - v - w, v, w);
}

TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                        const Vec3& c) {
  return closest_point_on_triangle(p, PreparedTriangle::of(a, b, c));
}

}  // namespace lodforge
