// Ray-triangle crossing: Moeller & Trumbore, "Fast, minimum storage
// ray/triangle intersection" (Journal of Graphics Tools, 1997). The edge
// vectors and the determinant in double precision: their float rounding is
// what lets a ray through a shared edge fall between two triangles.
#include "lodforge/metrics/ray.h"

namespace lodforge {
namespace {

struct D3 {
  double x, y, z;
};
D3 sub(const Vec3& p, const Vec3& q) {
  return {double(p.x) - q.x, double(p.y) - q.y, double(p.z) - q.z};
}
D3 cross(const D3& a, const D3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(const D3& a, const D3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

}  // namespace

double Ray::hit(const Vec3& a, const Vec3& b, const Vec3& c) const {
  const D3 e1 = sub(b, a), e2 = sub(c, a);
  const D3 d{direction.x, direction.y, direction.z};
  const D3 p = cross(d, e2);
  const double det = dot(e1, p);
  if (det == 0) return -1;
  const double inv_det = 1.0 / det;
  const D3 s = sub(origin, a);
  const double u = dot(s, p) * inv_det;
  if (u < 0 || u > 1) return -1;
  const D3 q = cross(s, e1);
  const double v = dot(d, q) * inv_det;
  if (v < 0 || u + v > 1) return -1;
  const double t = dot(e2, q) * inv_det;
  return t >= 0 ? t : -1;
}

}  // namespace lodforge
