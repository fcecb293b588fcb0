#pragma once
/// The error quadric of Garland and Heckbert, "Surface Simplification Using
/// Quadric Error Metrics" (SIGGRAPH 1997): the sum of weighted squared
/// distances to a set of planes, as one symmetric 4x4 form.
#include <algorithm>
#include <array>

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

/// Regularisation of quadric_minimum, as a fraction of the trace of A:
/// Lindstrom ("Out-of-Core Simplification of Large Polygonal Models",
/// SIGGRAPH 2000) drops the eigenvalues below 1e-3 of the largest.
inline constexpr double kQuadricRankTolerance = 1e-3;

/// The minimum of q regularised towards x0: the minimum of
/// Q(x) + lambda |x - x0|^2 with lambda = kQuadricRankTolerance x trace(A),
/// one 3x3 solve. Along directions where A is strong (eigenvalue >> lambda)
/// this is the quadric's optimum; along weak ones (a flat or straight
/// region, where Q has no unique minimum) it stays at x0, like Lindstrom's
/// truncated pseudo-inverse, without its eigen-decomposition. x0 itself when
/// A is zero or the system is not positive definite (non-finite input).
inline std::array<double, 3> quadric_minimum(const Quadric& q, const std::array<double, 3>& x0) {
  const double lambda = kQuadricRankTolerance * (q.a00 + q.a11 + q.a22);
  if (!(lambda > 0)) return x0;
  const double m00 = q.a00 + lambda, m11 = q.a11 + lambda, m22 = q.a22 + lambda;
  const double m01 = q.a01, m02 = q.a02, m12 = q.a12;
  // Solve M d = -(A x0 + b) for the step d from x0 (Cramer; M is positive definite).
  const double r0 = -(q.b0 + q.a00 * x0[0] + q.a01 * x0[1] + q.a02 * x0[2]);
  const double r1 = -(q.b1 + q.a01 * x0[0] + q.a11 * x0[1] + q.a12 * x0[2]);
  const double r2 = -(q.b2 + q.a02 * x0[0] + q.a12 * x0[1] + q.a22 * x0[2]);
  const double c00 = m11 * m22 - m12 * m12, c01 = m02 * m12 - m01 * m22;
  const double c02 = m01 * m12 - m02 * m11, c11 = m00 * m22 - m02 * m02;
  const double c12 = m01 * m02 - m00 * m12, c22 = m00 * m11 - m01 * m01;
  const double det = m00 * c00 + m01 * c01 + m02 * c02;
  if (!(det > 0)) return x0;
  return {x0[0] + (c00 * r0 + c01 * r1 + c02 * r2) / det,
          x0[1] + (c01 * r0 + c11 * r1 + c12 * r2) / det,
          x0[2] + (c02 * r0 + c12 * r1 + c22 * r2) / det};
}

}  // namespace lodforge
