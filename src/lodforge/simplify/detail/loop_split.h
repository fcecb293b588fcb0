#pragma once
/// Schroeder's recursive loop splitting, the re-triangulation of a hole in
/// vertex_decimation (see vertex_decimation.h for the contract). Internal to
/// simplify/.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "lodforge/core/math.h"
#include "lodforge/simplify/vertex_decimation.h"

namespace lodforge::detail::decimation {

/// Loop vertices of a fan: n for a ring, n + 1 for an open fan.
constexpr int kMaxLoop = static_cast<int>(kMaxDecimationValence) + 1;

/// A new triangle by its three polygon indices.
using Tri8 = std::array<std::uint8_t, 3>;

/// One polygon to re-triangulate: the whole loop, or one side of a feature line.
struct Side {
  int m = 0;                                   // polygon vertices
  std::array<std::uint32_t, kMaxLoop> poly{};  // mesh vertices, loop order
  std::array<Vec3, kMaxLoop> p{};              // their positions
  // tris[j] had polygon edge (j, j+1): m of them for a ring, m - 1 otherwise.
  std::array<std::uint32_t, kMaxLoop> tris{};
  int ntris = 0;
  Vec3 normal;  // sum of the side triangles' cross products, then its unit vector
  // Polygon vertices in the average plane (orthonormal u, w with u x w =
  // normal, origin poly[0]): the split-plane tests are 2D orientation tests.
  // Three more entries: the split search reads them four at a time.
  std::array<float, kMaxLoop + 3> x{}, y{};
  std::array<float, kMaxLoop + 3> px{}, py{}, pz{};  // p, component-wise
};

/// Four floats (GCC/Clang vector extension: one SSE register on x86-64, plain
/// code elsewhere); comparisons give Int4 lanes of -1 (true) or 0.
using Float4 = float __attribute__((vector_size(16)));
using Int4 = std::int32_t __attribute__((vector_size(16)));

inline Float4 load4(const float* p) {
  Float4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline Float4 sqrt4(Float4 v) {
  for (int l = 0; l < 4; ++l) v[l] = std::sqrt(v[l]);
  return v;
}

inline Float4 splat(float x) {
  return Float4{x, x, x, x};
}

inline Float4 infinity4() {
  return splat(std::numeric_limits<float>::infinity());
}

/// Lane-wise std::min(a, b) (b if a is NaN; a if b is NaN).
inline Float4 min4(Float4 a, Float4 b) {
  return b < a ? b : a;
}

/// Signed distance of point k to the split plane of line (a, a + l) (up to the
/// scale below), in the average plane's basis: positive on the left of the line.
inline Float4 split_distance(Float4 kx, Float4 ky, Float4 ax, Float4 ay, Float4 lx, Float4 ly) {
  return (kx - ax) * ly - (ky - ay) * lx;
}

/// The split plane normal is line x normal = (ly, -lx) in the plane's basis;
/// aspect ratio = smallest signed distance / this scale (the normal's length
/// times the line's length in 3D, d).
inline Float4 split_scale(Float4 lx, Float4 ly, Float4 dx, Float4 dy, Float4 dz) {
  return sqrt4((lx * lx + ly * ly) * (dx * dx + dy * dy + dz * dz));
}

// Recursive loop splitting (Schroeder 1992 §"Triangulation"): a split line
// joins two non-neighbouring loop vertices; the split plane contains it and is
// orthogonal to the average plane. A split is valid if the loop vertices
// between the ends (in loop order) lie strictly on the positive side of the
// split plane and the others strictly on the negative side (for a loop
// counter-clockwise around the normal: this also rules out splits through the
// outside of a concave loop) and the line is not already a mesh edge. Among the
// valid ones the largest aspect ratio (smallest distance of a loop vertex to
// the split plane over the line's length) wins.
/// Appends to `out` a triangulation of the polygon idx[0 .. m) of `side`
/// (indices into it), or returns false if some sub-polygon has no valid
/// split line. `edge_exists(a, b)` tells whether mesh vertices a and b are
/// joined already; `final`: the winner of each split must not be such an
/// edge (the plan of a queued vertex skips that costly check). `top`: idx is
/// the identity over the whole side.
template <class EdgeExists>
bool split_loop(const Side& side, const std::uint8_t* idx, int m, std::vector<Tri8>& out,
                bool final, const EdgeExists& edge_exists, bool check_edges = false,
                bool top = false) {
  if (m == 3) {
    out.push_back({idx[0], idx[1], idx[2]});
    return true;
  }
  float best = 0;
  int bi = -1, bj = -1;
  // Split line (i, j), of this scale, with this smallest signed distance of
  // another vertex to its plane: the best so far if valid and better.
  auto consider = [&](int i, int j, float scale, float worst) {
    if (!(scale > 0) || !(worst > best * scale)) return;
    if (check_edges && edge_exists(side.poly[idx[i]], side.poly[idx[j]])) return;
    best = worst / scale;
    bi = i;
    bj = j;
  };
  if (m == 4) {
    // The two split lines of a quad, (0, 2) and (1, 3), in lanes 0 and 1:
    // the vertices in lane order from i (rotated by 0), the one between (1),
    // j (2) and the other one (3).
    const float q[5][4] = {{side.x[idx[0]], side.x[idx[1]], side.x[idx[2]], side.x[idx[3]]},
                           {side.y[idx[0]], side.y[idx[1]], side.y[idx[2]], side.y[idx[3]]},
                           {side.px[idx[0]], side.px[idx[1]], side.px[idx[2]], side.px[idx[3]]},
                           {side.py[idx[0]], side.py[idx[1]], side.py[idx[2]], side.py[idx[3]]},
                           {side.pz[idx[0]], side.pz[idx[1]], side.pz[idx[2]], side.pz[idx[3]]}};
    auto rotated = [&](int c, int r) { return Float4{q[c][r], q[c][(r + 1) % 4], 0, 0}; };
    const Float4 ax = rotated(0, 0), ay = rotated(1, 0);
    const Float4 lx = rotated(0, 2) - ax, ly = rotated(1, 2) - ay;
    const Float4 scale = split_scale(lx, ly, rotated(2, 2) - rotated(2, 0),
                                     rotated(3, 2) - rotated(3, 0), rotated(4, 2) - rotated(4, 0));
    const Float4 worst =
        min4(min4(infinity4(), split_distance(rotated(0, 1), rotated(1, 1), ax, ay, lx, ly)),
             -split_distance(rotated(0, 3), rotated(1, 3), ax, ay, lx, ly));
    consider(0, 2, scale[0], worst[0]);
    consider(1, 3, scale[1], worst[1]);
  } else {
    // This polygon's vertices, contiguous (uninitialised scratch: no Vec3;
    // three more entries, read by the last group of four, set to 0). The whole
    // side (top, idx is the identity) is read in place.
    float gx[kMaxLoop + 3], gy[kMaxLoop + 3], gpx[kMaxLoop + 3], gpy[kMaxLoop + 3],
        gpz[kMaxLoop + 3];
    const float *X = side.x.data(), *Y = side.y.data();
    const float *PX = side.px.data(), *PY = side.py.data(), *PZ = side.pz.data();
    if (!top) {
      for (int k = 0; k < m; ++k) {
        gx[k] = side.x[idx[k]];
        gy[k] = side.y[idx[k]];
        gpx[k] = side.px[idx[k]];
        gpy[k] = side.py[idx[k]];
        gpz[k] = side.pz[idx[k]];
      }
      for (int k = m; k < m + 3; ++k) gx[k] = gy[k] = gpx[k] = gpy[k] = gpz[k] = 0;
      X = gx;
      Y = gy;
      PX = gpx;
      PY = gpy;
      PZ = gpz;
    }
    // The split lines from i to four j at once (lanes past the last j are
    // computed and ignored).
    const Int4 lane = {0, 1, 2, 3};
    for (int i = 0; i < m; ++i) {
      const Float4 ax = splat(X[i]), ay = splat(Y[i]);
      for (int jb = i + 2, jend = i == 0 ? m - 1 : m; jb < jend; jb += 4) {
        const Int4 j = jb + lane;
        const Float4 lx = load4(X + jb) - ax, ly = load4(Y + jb) - ay;
        const Float4 scale = split_scale(lx, ly, load4(PX + jb) - PX[i], load4(PY + jb) - PY[i],
                                         load4(PZ + jb) - PZ[i]);
        // The first half (i, j) must be on the positive side, the rest
        // negative: k < i and k > j negative, i < k < j positive.
        auto distance = [&](int k) {
          return split_distance(splat(X[k]), splat(Y[k]), ax, ay, lx, ly);
        };
        Float4 worst = infinity4();
        for (int k = 0; k < i; ++k) worst = min4(worst, -distance(k));
        for (int k = i + 1; k < jb; ++k) worst = min4(worst, distance(k));
        for (int k = jb; k < m; ++k) {
          Float4 d = distance(k);
          d = k > j ? -d : d;
          worst = min4(worst, k == j ? infinity4() : d);
        }
        for (int l = 0; l < 4 && jb + l < jend; ++l) consider(i, jb + l, scale[l], worst[l]);
      }
    }
  }
  if (bi < 0) return false;
  // Looking up edges is the costly part: do it for the winner only, and search
  // again among the lines that are not edges if the winner is one.
  if (final && !check_edges && edge_exists(side.poly[idx[bi]], side.poly[idx[bj]]))
    return split_loop(side, idx, m, out, true, edge_exists, true, top);
  std::array<std::uint8_t, kMaxLoop> half;
  int h = 0;
  for (int k = bi; k <= bj; ++k) half[h++] = idx[k];
  if (h == 3)
    out.push_back({half[0], half[1], half[2]});
  else if (!split_loop(side, half.data(), h, out, final, edge_exists))
    return false;
  h = 0;
  for (int k = bj; k < m; ++k) half[h++] = idx[k];
  for (int k = 0; k <= bi; ++k) half[h++] = idx[k];
  if (h == 3) {
    out.push_back({half[0], half[1], half[2]});
    return true;
  }
  return split_loop(side, half.data(), h, out, final, edge_exists);
}

/// How triangulate_side() ended.
enum class Triangulation { kDone, kFlat, kNoSplit };

/// Projects `side` into its average plane (normalising side.normal) and
/// triangulates it (see split_loop()); kFlat if the side has no normal.
template <class EdgeExists>
Triangulation triangulate_side(Side& side, std::vector<Tri8>& out, bool final,
                               const EdgeExists& edge_exists) {
  float l = length(side.normal);
  if (!(l > 0)) return Triangulation::kFlat;
  Vec3 n = side.normal / l;
  side.normal = n;
  Vec3 u = normalized(cross(n, std::abs(n.x) < 0.6f ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
  Vec3 w = cross(n, u);
  const Vec3 origin = side.p[0];
  std::array<std::uint8_t, kMaxLoop> idx;
  for (int j = 0; j < side.m; ++j) {
    idx[j] = static_cast<std::uint8_t>(j);
    Vec3 d = side.p[j] - origin;
    side.x[j] = dot(d, u);
    side.y[j] = dot(d, w);
    side.px[j] = side.p[j].x;
    side.py[j] = side.p[j].y;
    side.pz[j] = side.p[j].z;
  }
  if (!split_loop(side, idx.data(), side.m, out, final, edge_exists, false, true))
    return Triangulation::kNoSplit;
  return Triangulation::kDone;
}

}  // namespace lodforge::detail::decimation
