#include "lodforge/core/math.h"

namespace lodforge {

Mat4 Mat4::translation(const Vec3& t) {
  Mat4 r;
  r.m[0][3] = t.x;
  r.m[1][3] = t.y;
  r.m[2][3] = t.z;
  return r;
}

Mat4 Mat4::scale(const Vec3& s) {
  Mat4 r;
  r.m[0][0] = s.x;
  r.m[1][1] = s.y;
  r.m[2][2] = s.z;
  return r;
}

Mat4 Mat4::rotation(const Vec3& axis, float angle) {
  Vec3 a = normalized(axis);
  Mat4 r;
  if (a == Vec3{}) return r;
  double c = std::cos(double(angle)), s = std::sin(double(angle)), t = 1 - c;
  double x = a.x, y = a.y, z = a.z;
  r.m[0][0] = float(t * x * x + c);
  r.m[0][1] = float(t * x * y - s * z);
  r.m[0][2] = float(t * x * z + s * y);
  r.m[1][0] = float(t * x * y + s * z);
  r.m[1][1] = float(t * y * y + c);
  r.m[1][2] = float(t * y * z - s * x);
  r.m[2][0] = float(t * x * z - s * y);
  r.m[2][1] = float(t * y * z + s * x);
  r.m[2][2] = float(t * z * z + c);
  return r;
}

Mat4 Mat4::from_vrml(const float* v) {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[j][i] = v[i * 4 + j];
  return r;
}

Mat4 Mat4::operator*(const Mat4& o) const {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += double(m[i][k]) * o.m[k][j];
      r.m[i][j] = float(s);
    }
  return r;
}

Vec3 Mat4::transform_point(const Vec3& p) const {
  float w = m[3][0] * p.x + m[3][1] * p.y + m[3][2] * p.z + m[3][3];
  Vec3 r{m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
         m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
         m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
  return (w != 0 && w != 1) ? r / w : r;
}

Vec3 Mat4::transform_vector(const Vec3& v) const {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
          m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

Mat4 Mat4::normal_matrix() const {
  // Cofactor matrix of the upper 3x3 equals det * inverse-transpose; the scale
  // does not matter for normals, which are re-normalised by the caller.
  const auto& a = m;
  Mat4 r;
  r.m[0][0] = a[1][1] * a[2][2] - a[1][2] * a[2][1];
  r.m[0][1] = a[1][2] * a[2][0] - a[1][0] * a[2][2];
  r.m[0][2] = a[1][0] * a[2][1] - a[1][1] * a[2][0];
  r.m[1][0] = a[0][2] * a[2][1] - a[0][1] * a[2][2];
  r.m[1][1] = a[0][0] * a[2][2] - a[0][2] * a[2][0];
  r.m[1][2] = a[0][1] * a[2][0] - a[0][0] * a[2][1];
  r.m[2][0] = a[0][1] * a[1][2] - a[0][2] * a[1][1];
  r.m[2][1] = a[0][2] * a[1][0] - a[0][0] * a[1][2];
  r.m[2][2] = a[0][0] * a[1][1] - a[0][1] * a[1][0];
  float det = a[0][0] * r.m[0][0] + a[0][1] * r.m[0][1] + a[0][2] * r.m[0][2];
  if (det == 0) return {};
  if (det < 0)
    for (auto& row : r.m)
      for (auto& x : row) x = -x;
  return r;
}

float Mat4::max_scale() const {
  float s = 0;
  for (int j = 0; j < 3; ++j) s = std::max(s, length(Vec3{m[0][j], m[1][j], m[2][j]}));
  return s;
}

BoxSphere box_centred_sphere(std::span<const Vec3> points) {
  Box3 box;
  for (const Vec3& p : points) box.add(p);
  if (box.empty()) return {};
  BoxSphere s{box.center(), 0};
  for (const Vec3& p : points) s.radius = std::max(s.radius, double(length(p - s.center)));
  return s;
}

}  // namespace lodforge
