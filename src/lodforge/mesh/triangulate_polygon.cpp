// Polygon triangulation by ear clipping on the best-fit plane.
//
// The plane normal is Newell's (Sutherland, Sproull & Schumacker, "A
// Characterization of Ten Hidden-Surface Algorithms", 1974), which is exact for
// planar polygons and a least-squares-like average for bent ones, and always
// points so that the polygon winds counter-clockwise around it. The polygon is
// projected onto that plane and cut into ears (Meisters, "Polygons have ears",
// 1975). Up to kBestEarLimit corners, among all current ears the best-shaped
// one is clipped, which avoids the slivers of first-ear clipping; ear flags
// are updated only for the two neighbours of a clipped corner, so the run is
// O(n^2). Larger polygons: a convex one is cut in O(n) (triangulate_convex),
// any other by first-ear clipping with a grid of the corners that can block
// an ear (GridEarClipper).
//
// Quads follow the original LODCreator rule:
//
//   quad is ...                         | result
//   ------------------------------------+----------------------------------------
//   convex, bent <= quad_split_angle    | kept (keep_as_quad), triangles along
//                                       | the diagonal of smaller bend
//   convex, bent more                   | split along the diagonal of smaller bend
//   concave                             | split along the only valid diagonal
//   neither diagonal valid (bow-tie...) | general ear clipping, flagged
//
// "Bent" is the larger of the two dihedral angles (one per diagonal), because a
// renderer given a quad may split it along either.
#include "lodforge/mesh/triangulate_polygon.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

namespace lodforge {
namespace {

struct P2 {
  double x, y;
};

double orient(const P2& a, const P2& b, const P2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

struct D3 {
  double x = 0, y = 0, z = 0;
};

D3 to_d3(const Vec3& v) {
  return {v.x, v.y, v.z};
}
D3 sub(const D3& a, const D3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
D3 cross3(const D3& a, const D3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot3(const D3& a, const D3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
double len3(const D3& a) {
  return std::sqrt(dot3(a, a));
}

/// Angle between the normals of triangles (a,b,c) and (a,c,d) in 3D.
double dihedral(const D3& a, const D3& b, const D3& c, const D3& d) {
  D3 n1 = cross3(sub(b, a), sub(c, a));
  D3 n2 = cross3(sub(c, a), sub(d, a));
  double l = len3(n1) * len3(n2);
  if (l <= 0) return kPi;
  return std::acos(std::clamp(dot3(n1, n2) / l, -1.0, 1.0));
}

/// Shape quality of a 2D triangle: 1 for equilateral, 0 for degenerate.
double quality(const P2& a, const P2& b, const P2& c) {
  double area2 = orient(a, b, c);
  double s = (b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y) + (c.x - b.x) * (c.x - b.x) +
             (c.y - b.y) * (c.y - b.y) + (a.x - c.x) * (a.x - c.x) + (a.y - c.y) * (a.y - c.y);
  return s > 0 ? 2.0 * std::sqrt(3.0) * area2 / s : 0.0;
}

// Up to this many corners the best-shaped ear is clipped each time (O(n^2));
// beyond, the first ear met (GridEarClipper).
constexpr std::size_t kBestEarLimit = 256;

class EarClipper {
 public:
  EarClipper(std::vector<P2> pts, double eps) : p_(std::move(pts)), eps_(eps) {
    std::size_t n = p_.size();
    prev_.resize(n);
    next_.resize(n);
    ear_.assign(n, false);
    score_.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      prev_[i] = static_cast<std::uint32_t>((i + n - 1) % n);
      next_[i] = static_cast<std::uint32_t>((i + 1) % n);
    }
    for (std::uint32_t i = 0; i < n; ++i) update(i);
  }

  void run(TriangulateResult& out) {
    std::size_t remaining = p_.size();
    std::uint32_t start = 0;
    while (remaining > 3) {
      std::uint32_t best = pick(start, out);
      std::uint32_t a = prev_[best], c = next_[best];
      emit(a, best, c, out);
      next_[a] = c;
      prev_[c] = a;
      start = a;
      --remaining;
      update(a);
      update(c);
    }
    emit(prev_[start], start, next_[start], out);
  }

 private:
  bool convex(std::uint32_t i) const { return orient(p_[prev_[i]], p_[i], p_[next_[i]]) > eps_; }

  void update(std::uint32_t i) {
    std::uint32_t a = prev_[i], c = next_[i];
    ear_[i] = convex(i);
    score_[i] = quality(p_[a], p_[i], p_[c]);
    if (!ear_[i]) return;
    const P2 &pa = p_[a], &pb = p_[i], &pc = p_[c];
    for (std::uint32_t j = next_[c]; j != a; j = next_[j]) {
      const P2& q = p_[j];
      // Corners coinciding with the ear's corners (bridged holes) do not block it.
      auto same = [](const P2& u, const P2& v) { return u.x == v.x && u.y == v.y; };
      if (same(q, pa) || same(q, pb) || same(q, pc)) continue;
      if (orient(pa, pb, q) >= -eps_ && orient(pb, pc, q) >= -eps_ && orient(pc, pa, q) >= -eps_) {
        ear_[i] = false;
        return;
      }
    }
  }

  /// The corner to clip: the best ear, else (not simple) the best convex
  /// corner, else (degenerate) the corner with the largest turn.
  std::uint32_t pick(std::uint32_t start, TriangulateResult& out) const {
    std::uint32_t best_ear = kNone, best_convex = kNone, best_any = start;
    double ear_score = -1, convex_score = -1, any_score = -std::numeric_limits<double>::max();
    std::uint32_t i = start;
    do {
      double o = orient(p_[prev_[i]], p_[i], p_[next_[i]]);
      if (ear_[i] && score_[i] > ear_score) ear_score = score_[i], best_ear = i;
      if (o > eps_ && score_[i] > convex_score) convex_score = score_[i], best_convex = i;
      if (o > any_score) any_score = o, best_any = i;
      i = next_[i];
    } while (i != start);
    if (best_ear != kNone) return best_ear;
    out.not_simple = true;
    if (best_convex != kNone) return best_convex;
    out.degenerate = true;
    return best_any;
  }

  void emit(std::uint32_t a, std::uint32_t b, std::uint32_t c, TriangulateResult& out) const {
    if (orient(p_[a], p_[b], p_[c]) <= eps_) out.degenerate = true;
    out.triangles.push_back({a, b, c});
  }

  static constexpr std::uint32_t kNone = lodforge::kNone;
  std::vector<P2> p_;
  double eps_;
  std::vector<std::uint32_t> prev_, next_;
  std::vector<bool> ear_;
  std::vector<double> score_;
};

// Ear clipping for large polygons, after Held's FIST ("FIST: Fast
// Industrial-Strength Triangulation of Polygons", 2001) and earcut: ears are
// taken as a walk around the polygon meets them, and an ear test looks only
// at the corners that can block an ear, the non-convex ones, found through a
// uniform grid. A convex polygon has none, so it takes O(n); a polygon with
// r non-convex corners spread evenly takes about O(n) ear tests of O(1 + r/n)
// grid entries each. The worst case stays quadratic: ears whose boxes span
// many non-convex corners (a comb whose teeth stand on one long straight
// edge of collinear corners). Corners only turn from non-convex to convex as ears go,
// so the grid is built once, and an entry found stale (its corner clipped or
// convex) is dropped from its cell.
class GridEarClipper {
 public:
  GridEarClipper(std::vector<P2> pts, double eps) : p_(std::move(pts)), eps_(eps) {
    const std::size_t n = p_.size();
    prev_.resize(n);
    next_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      prev_[i] = static_cast<std::uint32_t>((i + n - 1) % n);
      next_[i] = static_cast<std::uint32_t>((i + 1) % n);
    }
    removed_.assign(n, 0);
    blocking_.assign(n, 0);
    std::vector<std::uint32_t> blockers;
    for (std::uint32_t i = 0; i < n; ++i)
      if (!convex(i)) blocking_[i] = 1, blockers.push_back(i);
    build_grid(blockers);
  }

  void run(TriangulateResult& out) {
    std::size_t remaining = p_.size();
    std::uint32_t v = 0;
    std::size_t tried = 0;  // corners tried since the last clip
    while (remaining > 3) {
      if (tried < remaining) {
        if (!is_ear(v)) {
          v = next_[v];
          ++tried;
          continue;
        }
      } else {
        v = fallback(v, remaining, out);
      }
      const std::uint32_t a = prev_[v], c = next_[v];
      emit(a, v, c, out);
      next_[a] = c;
      prev_[c] = a;
      removed_[v] = 1;
      --remaining;
      for (std::uint32_t k : {a, c})
        if (blocking_[k] && convex(k)) blocking_[k] = 0;
      // Walking on past c keeps the ears local (each turn clips about every
      // other corner); staying at a or c would make a fan of ever larger
      // triangles around it, and a vertex of huge valence.
      v = next_[c];
      tried = 0;
    }
    emit(prev_[v], v, next_[v], out);
  }

 private:
  // Strictly convex: corners of large polygons with float coordinates may
  // turn by less than eps_ and are ears all the same.
  bool convex(std::uint32_t i) const { return orient(p_[prev_[i]], p_[i], p_[next_[i]]) > 0; }

  void build_grid(const std::vector<std::uint32_t>& blockers) {
    lo_ = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
    P2 hi{-std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()};
    for (const P2& q : p_) {
      lo_ = {std::min(lo_.x, q.x), std::min(lo_.y, q.y)};
      hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
    }
    // About one blocking corner per cell, at most 1024 cells a side.
    const double w = std::max(hi.x - lo_.x, 0.0), h = std::max(hi.y - lo_.y, 0.0);
    const double side = std::sqrt(static_cast<double>(std::max<std::size_t>(blockers.size(), 1)));
    const double aspect = w > 0 && h > 0 ? std::sqrt(w / h) : 1.0;
    cols_ = static_cast<int>(std::clamp(side * aspect, 1.0, 1024.0));
    rows_ = static_cast<int>(std::clamp(side / aspect, 1.0, 1024.0));
    cell_w_ = w > 0 ? w / cols_ : 1;
    cell_h_ = h > 0 ? h / rows_ : 1;
    start_.assign(static_cast<std::size_t>(cols_) * rows_ + 1, 0);
    for (std::uint32_t i : blockers) ++start_[cell_of(p_[i]) + 1];
    for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
    entries_.resize(blockers.size());
    end_.assign(start_.begin(), start_.end() - 1);
    for (std::uint32_t i : blockers) entries_[end_[cell_of(p_[i])]++] = i;
  }
  int column(double x) const {
    return static_cast<int>(std::clamp((x - lo_.x) / cell_w_, 0.0, double(cols_ - 1)));
  }
  int row(double y) const {
    return static_cast<int>(std::clamp((y - lo_.y) / cell_h_, 0.0, double(rows_ - 1)));
  }
  std::size_t cell_of(const P2& q) const {
    return static_cast<std::size_t>(row(q.y)) * cols_ + column(q.x);
  }

  // Corner b is an ear: convex, and no corner that can block it lies in or
  // on its triangle (corners at the ear's corners, bridged holes, do not).
  bool is_ear(std::uint32_t b) {
    if (!convex(b)) return false;
    const std::uint32_t a = prev_[b], c = next_[b];
    const P2 &pa = p_[a], &pb = p_[b], &pc = p_[c];
    auto same = [](const P2& u, const P2& v) { return u.x == v.x && u.y == v.y; };
    const int c0 = column(std::min({pa.x, pb.x, pc.x})), c1 = column(std::max({pa.x, pb.x, pc.x}));
    const int r0 = row(std::min({pa.y, pb.y, pc.y})), r1 = row(std::max({pa.y, pb.y, pc.y}));
    for (int r = r0; r <= r1; ++r)
      for (int col = c0; col <= c1; ++col) {
        const std::size_t cell = static_cast<std::size_t>(r) * cols_ + col;
        for (std::uint32_t k = start_[cell]; k < end_[cell]; ++k) {
          const std::uint32_t j = entries_[k];
          if (removed_[j] || !blocking_[j]) {
            entries_[k--] = entries_[--end_[cell]];
            continue;
          }
          if (j == a || j == b || j == c) continue;
          const P2& q = p_[j];
          if (same(q, pa) || same(q, pb) || same(q, pc)) continue;
          if (orient(pa, pb, q) >= -eps_ && orient(pb, pc, q) >= -eps_ &&
              orient(pc, pa, q) >= -eps_)
            return false;
        }
      }
    return true;
  }

  // No ear in a whole turn: the polygon is not simple (clip a convex
  // corner) or degenerate (clip the corner with the largest turn).
  std::uint32_t fallback(std::uint32_t v, std::size_t remaining, TriangulateResult& out) const {
    std::uint32_t best = v;
    double best_turn = -std::numeric_limits<double>::max();
    for (std::size_t k = 0; k < remaining; ++k, v = next_[v]) {
      if (convex(v)) {
        out.not_simple = true;
        return v;
      }
      const double o = orient(p_[prev_[v]], p_[v], p_[next_[v]]);
      if (o > best_turn) best_turn = o, best = v;
    }
    out.not_simple = true;
    out.degenerate = true;
    return best;
  }

  void emit(std::uint32_t a, std::uint32_t b, std::uint32_t c, TriangulateResult& out) const {
    if (orient(p_[a], p_[b], p_[c]) <= eps_) out.degenerate = true;
    out.triangles.push_back({a, b, c});
  }

  std::vector<P2> p_;
  double eps_;
  std::vector<std::uint32_t> prev_, next_;
  std::vector<std::uint8_t> removed_, blocking_;
  P2 lo_{};
  double cell_w_ = 1, cell_h_ = 1;
  int cols_ = 1, rows_ = 1;
  /// Cell k's entries are entries_[start_[k], end_[k]).
  std::vector<std::uint32_t> start_, end_, entries_;
};

// A convex polygon cut in O(n): each turn around the ring takes the
// triangles of every other corner, so the triangles are as balanced as the
// polygon allows. Convex within the rounding of float input: a corner of a
// finely sampled curve may turn back by up to about its edges' length times
// float resolution at the polygon's `extent`. Returns false, doing nothing,
// if a corner turns back by more, or the polygon winds more than once.
bool triangulate_convex(const std::vector<P2>& p, double extent, double eps,
                        TriangulateResult& out) {
  const std::size_t n = p.size();
  double turning = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const P2 &a = p[(i + n - 1) % n], &b = p[i], &c = p[(i + 1) % n];
    const double ux = b.x - a.x, uy = b.y - a.y, vx = c.x - b.x, vy = c.y - b.y;
    const double rounding = (std::hypot(ux, uy) + std::hypot(vx, vy)) * extent * 1e-6;
    if (orient(a, b, c) < -std::max(eps, rounding)) return false;
    turning += std::atan2(ux * vy - uy * vx, ux * vx + uy * vy);
  }
  if (std::abs(turning - 2 * kPi) > 1e-3) return false;
  std::vector<std::uint32_t> ring(n), kept;
  for (std::size_t i = 0; i < n; ++i) ring[i] = static_cast<std::uint32_t>(i);
  auto emit = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (orient(p[a], p[b], p[c]) <= eps) out.degenerate = true;
    out.triangles.push_back({a, b, c});
  };
  while (ring.size() >= 3) {
    const std::size_t m = ring.size();
    kept.clear();
    for (std::size_t i = 0; i + 1 < m; i += 2) {
      kept.push_back(ring[i]);
      emit(ring[i], ring[i + 1], ring[(i + 2) % m]);
    }
    if (m % 2) kept.push_back(ring[m - 1]);
    if (m == 3) break;
    ring.swap(kept);
  }
  return true;
}

void fan(std::size_t n, TriangulateResult& out) {
  for (std::uint32_t i = 1; i + 1 < n; ++i) out.triangles.push_back({0, i, i + 1});
}

/// A polygon projected onto the plane of its Newell normal: corners
/// relative to the first (`q`, in 3D) and in the plane (`p`, counter-
/// clockwise), with the scale below which areas are rounding noise.
struct Projection {
  double extent = 0;  ///< largest coordinate difference from the first corner
  double eps = 0;     ///< twice an area below this is noise of float input
  D3 normal;          ///< unit; zero when `flat`
  bool flat = false;  ///< (almost) no area: nothing projected
};

/// Fills q and p (both of points.size()) unless the polygon is flat.
Projection project(std::span<const Vec3> points, std::span<D3> q, std::span<P2> p) {
  const std::size_t n = points.size();
  Projection out;
  // Newell normal, in double, about the first corner to limit cancellation.
  const D3 origin = to_d3(points[0]);
  for (std::size_t i = 0; i < n; ++i) {
    q[i] = sub(to_d3(points[i]), origin);
    out.extent = std::max({out.extent, std::abs(q[i].x), std::abs(q[i].y), std::abs(q[i].z)});
  }
  D3 normal;
  for (std::size_t i = 0; i < n; ++i) {
    const D3& a = q[i];
    const D3& b = q[(i + 1) % n];
    normal.x += (a.y - b.y) * (a.z + b.z);
    normal.y += (a.z - b.z) * (a.x + b.x);
    normal.z += (a.x - b.x) * (a.y + b.y);
  }
  const double nl = len3(normal);
  // Twice the polygon's area is nl; below this it is noise of float input.
  out.eps = out.extent * out.extent * 1e-12;
  if (!(out.extent > 0) || !(nl > out.eps) || !std::isfinite(nl)) {
    out.flat = true;
    return out;
  }
  out.normal = {normal.x / nl, normal.y / nl, normal.z / nl};
  // Orthonormal basis (u, v) of the plane with u x v = normal, so that the
  // projected polygon is counter-clockwise.
  const D3 axis = std::abs(out.normal.x) < 0.6 ? D3{1, 0, 0} : D3{0, 1, 0};
  D3 u = cross3(axis, out.normal);
  const double ul = len3(u);
  u = {u.x / ul, u.y / ul, u.z / ul};
  const D3 v = cross3(out.normal, u);
  for (std::size_t i = 0; i < n; ++i) p[i] = {dot3(q[i], u), dot3(q[i], v)};
  return out;
}

/// Storage for n items, on the stack for the triangles and quads that most
/// polygons are (no allocation on the common path).
template <class T>
class SmallBuffer {
 public:
  explicit SmallBuffer(std::size_t n) {
    if (n > small_.size()) big_.resize(n);
    items_ = n > small_.size() ? std::span<T>(big_) : std::span<T>(small_.data(), n);
  }
  std::span<T> span() { return items_; }
  std::vector<T> take() {
    return big_.empty() ? std::vector<T>(items_.begin(), items_.end()) : std::move(big_);
  }

 private:
  std::array<T, 4> small_;
  std::vector<T> big_;
  std::span<T> items_;
};

bool degenerate_triangle(const Projection& pr, std::span<const P2> p) {
  return pr.flat || orient(p[0], p[1], p[2]) <= pr.eps;
}

}  // namespace

bool triangle_is_degenerate(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 corners[3] = {a, b, c};
  std::array<D3, 3> q;
  std::array<P2, 3> p;
  return degenerate_triangle(project(corners, q, p), p);
}

TriangulateResult triangulate_polygon(std::span<const Vec3> points,
                                      const TriangulateOptions& options) {
  TriangulateResult out;
  const std::size_t n = points.size();
  if (n < 3) {
    out.degenerate = true;
    return out;
  }
  out.triangles.reserve(n - 2);
  SmallBuffer<D3> q_buffer(n);
  SmallBuffer<P2> p_buffer(n);
  const std::span<D3> q = q_buffer.span();
  const std::span<P2> p = p_buffer.span();
  const Projection pr = project(points, q, p);
  if (pr.flat) {
    out.degenerate = true;
    fan(n, out);
    return out;
  }
  out.normal = {static_cast<float>(pr.normal.x), static_cast<float>(pr.normal.y),
                static_cast<float>(pr.normal.z)};
  const double eps = pr.eps;

  if (n == 3) {
    out.triangles.push_back({0, 1, 2});
    out.degenerate = degenerate_triangle(pr, p);
    return out;
  }
  if (n == 4) {
    bool valid_a = orient(p[0], p[1], p[2]) > eps && orient(p[0], p[2], p[3]) > eps;
    bool valid_b = orient(p[1], p[2], p[3]) > eps && orient(p[1], p[3], p[0]) > eps;
    double bend_a = dihedral(q[0], q[1], q[2], q[3]);
    double bend_b = dihedral(q[1], q[2], q[3], q[0]);
    if (valid_a || valid_b) {
      bool use_a = valid_a && (!valid_b || bend_a <= bend_b);
      if (use_a) {
        out.triangles = {{0, 1, 2}, {0, 2, 3}};
      } else {
        out.triangles = {{1, 2, 3}, {1, 3, 0}};
      }
      out.keep_as_quad = options.keep_quads && valid_a && valid_b &&
                         std::max(bend_a, bend_b) <= options.quad_split_angle;
      return out;
    }
  }
  std::vector<P2> corners = p_buffer.take();
  if (n <= kBestEarLimit)
    EarClipper(std::move(corners), eps).run(out);
  else if (!triangulate_convex(corners, pr.extent, eps, out))
    GridEarClipper(std::move(corners), eps).run(out);
  return out;
}

TriangulateResult triangulate_polygon(std::span<const Vec3> positions,
                                      std::span<const std::uint32_t> indices,
                                      const TriangulateOptions& options) {
  SmallBuffer<Vec3> points(indices.size());
  for (std::size_t k = 0; k < indices.size(); ++k) {
    assert(indices[k] < positions.size());
    points.span()[k] = positions[indices[k]];
  }
  return triangulate_polygon(points.span(), options);
}

}  // namespace lodforge
