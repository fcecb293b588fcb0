#pragma once
/// A ray prepared for many box and triangle tests: the slab test of a search
/// structure's boxes and the exact crossing of a triangle. For first-hit
/// queries (mcoctree/mc_query.h, TriangleBvh::first_hit).
#include <array>
#include <utility>

#include "lodforge/core/math.h"

namespace lodforge {

/// The points origin + t * direction, t >= 0. Preconditions: origin finite,
/// direction unit (assert-free: callers check their input).
struct Ray {
  Vec3 origin, direction;
  Vec3 inv;                    ///< 1 / direction per axis (0 where flat)
  std::array<bool, 3> flat{};  ///< direction component zero

  Ray(const Vec3& o, const Vec3& unit) : origin(o), direction(unit) {
    for (int a = 0; a < 3; ++a) {
      flat[a] = unit[a] == 0;
      inv[a] = flat[a] ? 0 : 1 / unit[a];
    }
  }

  /// The t at which the ray enters the box [lo, hi] within [0, t_max] (0
  /// when the origin is inside), or -1 when it does not meet the box there.
  /// A zero direction component is tested by position, avoiding the 0 x inf
  /// of the plain slab formula (Kay & Kajiya 1986).
  float enter(const Vec3& lo, const Vec3& hi, float t_max) const {
    float t0 = 0, t1 = t_max;
    for (int a = 0; a < 3; ++a) {
      if (flat[a]) {
        if (origin[a] < lo[a] || origin[a] > hi[a]) return -1;
        continue;
      }
      float near = (lo[a] - origin[a]) * inv[a], far = (hi[a] - origin[a]) * inv[a];
      if (near > far) std::swap(near, far);
      t0 = std::max(t0, near);
      t1 = std::min(t1, far);
      if (t0 > t1) return -1;
    }
    return t0;
  }

  /// The t >= 0 at which the ray crosses the solid triangle (a, b, c), from
  /// either side, or -1: none (behind the origin, beside the triangle,
  /// parallel to its plane, or a degenerate triangle). Moeller & Trumbore
  /// (1997) in double precision, so that a ray through an edge two triangles
  /// share is seldom lost between them. Never throws.
  double hit(const Vec3& a, const Vec3& b, const Vec3& c) const;
};

}  // namespace lodforge
