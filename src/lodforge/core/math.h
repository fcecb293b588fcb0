#pragma once
/// Small fixed-size math for geometry: vectors, 4x4 matrices, boxes.
/// Floats are single precision like the file formats; accumulations that need
/// more precision convert explicitly.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>

namespace lodforge {

/// The index that names no vertex, triangle, node or value: all bits set.
inline constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

struct Vec2 {
  float x = 0, y = 0;
  Vec2 operator+(const Vec2& o) const { return {x + o.x, y + o.y}; }
  Vec2 operator*(float s) const { return {x * s, y * s}; }
  friend bool operator==(const Vec2&, const Vec2&) = default;
};

struct Vec3 {
  float x = 0, y = 0, z = 0;
  float& operator[](int i) { return (&x)[i]; }
  float operator[](int i) const { return (&x)[i]; }
  Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  Vec3 operator-() const { return {-x, -y, -z}; }
  Vec3 operator*(float s) const { return {x * s, y * s, z * s}; }
  Vec3 operator/(float s) const { return {x / s, y / s, z / s}; }
  Vec3& operator+=(const Vec3& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  Vec3& operator-=(const Vec3& o) {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  Vec3& operator*=(float s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
  friend bool operator==(const Vec3&, const Vec3&) = default;
};

inline Vec3 operator*(float s, const Vec3& v) {
  return v * s;
}
inline float dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(const Vec3& v) {
  return std::sqrt(dot(v, v));
}
inline float length_squared(const Vec3& v) {
  return dot(v, v);
}
/// Unit vector along v; the zero vector stays zero.
inline Vec3 normalized(const Vec3& v) {
  float l = length(v);
  return l > 0 ? v / l : Vec3{};
}
inline Vec3 min(const Vec3& a, const Vec3& b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3 max(const Vec3& a, const Vec3& b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
inline bool is_finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Axis-aligned box; empty until something is added.
struct Box3 {
  Vec3 lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
          std::numeric_limits<float>::max()};
  Vec3 hi{-std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
          -std::numeric_limits<float>::max()};
  bool empty() const { return lo.x > hi.x; }
  void add(const Vec3& p) {
    lo = min(lo, p);
    hi = max(hi, p);
  }
  void add(const Box3& b) {
    if (!b.empty()) {
      add(b.lo);
      add(b.hi);
    }
  }
  Vec3 center() const { return (lo + hi) * 0.5f; }
  Vec3 size() const { return empty() ? Vec3{} : hi - lo; }
  float diagonal() const { return empty() ? 0.f : length(hi - lo); }
};

/// A bounding sphere about the centre of its points' box, through the
/// farthest of them: how LOD ranges and screen coverages take an object's
/// extent (the same sphere wherever it is computed). No points: centre 0,
/// radius 0.
struct BoxSphere {
  Vec3 center;
  double radius = 0;
};
BoxSphere box_centred_sphere(std::span<const Vec3> points);

/// Column-vector 4x4 matrix stored row-major: m[row][col]; points transform as M * p.
/// VRML's SFMatrix is written row by row with the translation in the last row
/// (row-vector convention), so from_vrml/to_vrml transpose.
struct Mat4 {
  std::array<std::array<float, 4>, 4> m{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};

  static Mat4 identity() { return {}; }
  static Mat4 translation(const Vec3& t);
  static Mat4 scale(const Vec3& s);
  /// Rotation by `angle` radians about `axis` (need not be unit; zero axis = identity).
  static Mat4 rotation(const Vec3& axis, float angle);
  /// From the 16 floats of a VRML/Inventor SFMatrix (row-vector convention).
  static Mat4 from_vrml(const float* v16);

  Mat4 operator*(const Mat4& o) const;
  Vec3 transform_point(const Vec3& p) const;
  Vec3 transform_vector(const Vec3& v) const;
  /// Inverse-transpose of the upper 3x3, for normals; identity if singular.
  Mat4 normal_matrix() const;
  /// Largest scale factor of the upper 3x3 (length of the longest image of a unit axis).
  float max_scale() const;
  friend bool operator==(const Mat4&, const Mat4&) = default;
};

constexpr double kPi = 3.14159265358979323846;

}  // namespace lodforge
