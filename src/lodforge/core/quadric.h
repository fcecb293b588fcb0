#pragma once
/// The error quadric of Garland and Heckbert, "Surface Simplification Using
/// Quadric Error Metrics" (SIGGRAPH 1997): the sum of weighted squared
/// distances to a set of planes, as one symmetric 4x4 form.
#include <algorithm>

namespace lodforge {

/// Q(p) = p^T A p + 2 b.p + c with A symmetric (a00 a01 a02 a11 a12 a22).
/// The plane n.p + d = 0 with weight w contributes w (n.p + d)^2, that is
/// A += w n n^T, b += w d n, c += w d^2.
///
/// An aggregate without member initialisers, so that arrays of quadrics can
/// be allocated without being written: `Quadric{}` is the zero quadric, a
/// default-initialised `Quadric q;` is indeterminate.
struct Quadric {
  double a00, a01, a02, a11, a12, a22;
  double b0, b1, b2;
  double c;

  /// w (n.p + d)^2; n need not be unit (the form scales with |n|^2).
  static Quadric plane(double nx, double ny, double nz, double d, double w) {
    return {w * nx * nx, w * nx * ny, w * nx * nz, w * ny * ny, w * ny * nz,
            w * nz * nz, w * nx * d,  w * ny * d,  w * nz * d,  w * d * d};
  }

  Quadric& operator+=(const Quadric& o) {
    a00 += o.a00;
    a01 += o.a01;
    a02 += o.a02;
    a11 += o.a11;
    a12 += o.a12;
    a22 += o.a22;
    b0 += o.b0;
    b1 += o.b1;
    b2 += o.b2;
    c += o.c;
    return *this;
  }
  friend Quadric operator+(Quadric a, const Quadric& b) { return a += b; }

  /// Adds w (n.p + d)^2.
  void add_plane(double nx, double ny, double nz, double d, double w) {
    a00 += w * nx * nx;
    a01 += w * nx * ny;
    a02 += w * nx * nz;
    a11 += w * ny * ny;
    a12 += w * ny * nz;
    a22 += w * nz * nz;
    b0 += w * nx * d;
    b1 += w * ny * d;
    b2 += w * nz * d;
    c += w * d * d;
  }

  /// Q(x, y, z), clamped at 0 (rounding can make a sum of squares negative).
  double operator()(double x, double y, double z) const {
    const double ax = a00 * x + a01 * y + a02 * z;
    const double ay = a01 * x + a11 * y + a12 * z;
    const double az = a02 * x + a12 * y + a22 * z;
    return std::max(0.0, x * ax + y * ay + z * az + 2 * (b0 * x + b1 * y + b2 * z) + c);
  }
};

}  // namespace lodforge
